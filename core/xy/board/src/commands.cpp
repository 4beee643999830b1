// The handlers of the axis commands (docs/protocol.md "ID tables", Commands) that are neither
// parameters (parameters.cpp) nor path parts (path_commands.cpp): stop, jog, the four
// positioning commands, home, sleep and wake (G24), nop and clear_fault (G12). What they share:
// a handler only stores this cycle's command for the axis core (docs/board.md "One cycle
// (tick) in order" step 3) or refuses it, asking the core itself what it would refuse, and the
// first motion command clears the step counter's validity flag in FRAM before any step
// (docs/board.md "Step counter and boot", docs/storage.md "Step counters across power-off").
#include "core/xy/board/board.hpp"

#include "protocol/xy/codec/commands.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
namespace st = ap::xy_storage;
using xy_frame::HandlerStatus;

xy_frame::HandlerStatus Board::refuse(Axis a, c::CommandId id) {
  refused_[idx(a)] = static_cast<std::uint8_t>(id);
  return HandlerStatus::Refused;
}

bool Board::motion_permitted() {
  if (sleeping_) return false;
  // The saved step counter stops being trustworthy the moment the carriage may move, so
  // its validity flag is cleared in FRAM (verified) before the first step; if that write
  // fails, the motion is refused rather than leaving a stale "valid" counter behind.
  const st::SaveResult r = store_.begin_motion();
  if (!r.ok()) {
    fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
    return false;
  }
  return true;
}

xy_frame::HandlerStatus Board::set_axis_command(Axis a, c::CommandId id, const xy_axis::Command& cmd) {
  const std::size_t i = idx(a);
  pending_[i] = cmd;
  pending_id_[i] = id;
  return HandlerStatus::Done;
}

// What the axis core will do with this cycle's pending motion command (a dry run of its
// command check on a copy of the state: the core decides, the board does not re-implement it).
Board::Pending Board::pending_motion(std::size_t i) const {
  if (pending_[i].kind == xy_axis::CmdKind::None || pending_[i].kind == xy_axis::CmdKind::Stop) return Pending::None;
  xy_axis::Input dry;
  dry.cmd = pending_[i];
  dry.endstop_min = in_.endstop_min[i] != 0 ? 1 : 0;
  dry.endstop_max = in_.endstop_max[i] != 0 ? 1 : 0;
  dry.blocked = block_ != Block::None ? 1 : 0;
  dry.link_alive = 1;
  return xy_axis::step(axes_[i], dry, derived_.cfg[i]).out.error != xy_axis::Error::None ? Pending::Refused
                                                                                   : Pending::Accepted;
}

HandlerStatus Board::on_nop(void*, Axis, std::int32_t) { return HandlerStatus::Done; }

HandlerStatus Board::on_stop(void* ctx, Axis a, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  if (b->path_.active()) {
    // A stop of either axis stops the path: both axes share one S-curve (docs/cnc.md "Stops").
    b->stop_path_by_user();
    return HandlerStatus::Done;
  }
  return b->set_axis_command(a, c::CommandId::Stop, {xy_axis::CmdKind::Stop, 0, 0, 0});
}

HandlerStatus Board::on_jog(void* ctx, Axis a, std::int32_t data) {
  auto* b = static_cast<Board*>(ctx);
  if (b->path_.active()) return b->refuse(a, c::CommandId::Jog);  // the path holds both axes
  if (data == 0) return b->set_axis_command(a, c::CommandId::Jog, {xy_axis::CmdKind::Stop, 0, 0, 0});
  if (!b->motion_permitted()) return b->refuse(a, c::CommandId::Jog);
  const std::int8_t dir = data > 0 ? std::int8_t{1} : std::int8_t{-1};
  const std::uint8_t level = (data == c::kJogFast || data == -c::kJogFast) ? 1 : 0;
  return b->set_axis_command(a, c::CommandId::Jog, {xy_axis::CmdKind::Jog, dir, level, 0});
}

HandlerStatus Board::on_goto(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_absolute(a, c::CommandId::Goto, um, kLevelFast);
}
HandlerStatus Board::on_goto_slow(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_absolute(a, c::CommandId::GotoSlow, um, kLevelSlow);
}
HandlerStatus Board::on_move(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_relative(a, c::CommandId::Move, um, kLevelFast);
}
HandlerStatus Board::on_move_slow(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_relative(a, c::CommandId::MoveSlow, um, kLevelSlow);
}

// Thesis §7.7 and §8.2.2: both speed levels serve manual moves and positioning; goto/move run
// at the fast level, goto_slow/move_slow at the slow one (docs/protocol.md, the command table).
HandlerStatus Board::position_absolute(Axis a, c::CommandId id, std::int32_t um, std::uint8_t level) {
  if (path_.active()) return refuse(a, id);  // the path holds both axes
  const st::ParameterSet& p = store_.current();
  const bool x = a == Axis::X;
  const xy_axis::Converted t =
      xy_axis::target_to_usteps(um, x ? p.soft_min_x_um : p.soft_min_y_um, x ? p.soft_max_x_um : p.soft_max_y_um, derived_.mech);
  if (t.error != xy_axis::Error::None) return refuse(a, id);
  if (!motion_permitted()) return refuse(a, id);
  return set_axis_command(a, id, {xy_axis::CmdKind::MoveAbs, 0, level, t.value});
}

HandlerStatus Board::position_relative(Axis a, c::CommandId id, std::int32_t um, std::uint8_t level) {
  if (path_.active()) return refuse(a, id);  // the path holds both axes
  const xy_axis::Converted d = xy_axis::um_to_usteps(um, derived_.mech, xy_axis::Round::Nearest);
  if (d.error != xy_axis::Error::None) return refuse(a, id);
  if (!motion_permitted()) return refuse(a, id);
  return set_axis_command(a, id, {xy_axis::CmdKind::MoveRel, 0, level, d.value});
}

HandlerStatus Board::on_home(void* ctx, Axis a, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  if (b->path_.active()) return b->refuse(a, c::CommandId::Home);  // the path holds both axes
  // Homing mode 1 (towards the min endstop) is the only one built: 0 means the platform has no
  // homing, 2 (StallGuard) needs a calibration the thesis does not give and a DIAG1 input the
  // board does not read (docs/storage.md "Factory and user parameters").
  if (b->store_.current().homing_mode != kHomingModeEndstop) return b->refuse(a, c::CommandId::Home);
  if (!b->motion_permitted()) return b->refuse(a, c::CommandId::Home);
  return b->set_axis_command(a, c::CommandId::Home, {xy_axis::CmdKind::Home, 0, 0, 0});
}

HandlerStatus Board::on_periph_off(void* ctx, Axis, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  b->sleeping_ = true;
  // Sleep stops the path as `stop` does (docs/cnc.md "Stops"), here in the handler: a path
  // that has not moved yet drops its queue at once, so a command later in the same frame
  // finds no path (docs/echo-model.md "The coordinated path").
  if (b->path_.active()) b->stop_path_by_user();
  for (std::size_t i = 0; i < kAxes; ++i) {
    // A motion command earlier in this frame that the axis core would refuse (out of the
    // soft limits, toward an endstop, ...) is still reported as refused: the stop replaces
    // it, but the PC must not lose the typed error (docs/board.md "Echo content",
    // docs/echo-model.md "Decisions").
    if (b->pending_motion(i) == Pending::Refused) b->refused_[i] = static_cast<std::uint8_t>(b->pending_id_[i]);
    b->pending_[i] = {xy_axis::CmdKind::Stop, 0, 0, 0};
    b->pending_id_[i] = c::CommandId::PeriphOff;
  }
  return HandlerStatus::Done;
}

HandlerStatus Board::on_periph_on(void* ctx, Axis, std::int32_t) {
  static_cast<Board*>(ctx)->sleeping_ = false;
  return HandlerStatus::Done;
}

HandlerStatus Board::on_clear(void* ctx, Axis, std::int32_t) {
  static_cast<Board*>(ctx)->fault_ = 0;
  return HandlerStatus::Done;
}

}  // namespace ap::xy_board
