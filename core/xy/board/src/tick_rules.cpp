// The rules a tick applies around the axis core (docs/board.md "One cycle (tick) in order"
// steps 2, 4 and 5), apart from the handlers because they run every tick whether a frame came
// or not: the block causes with the battery's hysteresis and the exit from BLOCKED
// (docs/board.md "Main states", "Decisions on the seed's gaps" G16, G23), the BLE session
// (G15), the link watchdog (G15, docs/motion.md §7), both axes stepped with this cycle's
// command, the event each motion ends with, which the echo shows while the axis stands
// (docs/board.md "Echo content"; the decisions in docs/echo-model.md "Decisions"), the encoder
// zero after a completed homing (docs/motion.md "Homing and the encoder zero") and the motor
// outputs (G24). A running path drives the axes instead (path_commands.cpp).
#include "core/xy/board/board.hpp"

#include "helpers.hpp"

namespace ap::xy_board {

void Board::begin_of_cycle() {
  if (hw_.sample != nullptr) hw_.sample(hw_.ctx, in_);
  const std::uint16_t threshold = store_.current().low_battery_mv;
  if (in_.battery_mv < threshold) {
    battery_low_ = true;
  } else if (static_cast<std::uint32_t>(in_.battery_mv) >= static_cast<std::uint32_t>(threshold) + kBatteryHysteresisMv) {
    battery_low_ = false;
  }
  const Block was = block_;
  block_ = in_.usb ? Block::Usb : (in_.charger ? Block::Charger : (battery_low_ ? Block::Battery : Block::None));
  if (was != Block::None && block_ == Block::None) {
    // G16: back to user control with every axis at rest and nothing pending; the axis core
    // already dropped each axis's mode while blocked, so only the board's memory is cleared.
    for (std::size_t i = 0; i < kAxes; ++i) {
      axes_[i].mode = xy_axis::Mode::Idle;
      axes_[i].target = axes_[i].pos;
      event_[i] = AxisEvent::None;
    }
  }
  session_open_ = ble_state(in_.ble_status1, in_.ble_status2) == BleState::Session;
}

void Board::step_axes() {
  const bool was_alive = xy_axis::link_alive(watchdog_);
  watchdog_ = xy_axis::watchdog_tick(watchdog_, frame_this_cycle_);
  const bool alive = xy_axis::link_alive(watchdog_);
  if (was_alive && !alive) ++counters_.watchdog_expiries;
  if (path_.active()) {
    // The path drives both axes; their own motion commands are refused meanwhile.
    step_path(alive);
    return;
  }
  for (std::size_t i = 0; i < kAxes; ++i) {
    xy_axis::Input in;
    in.cmd = pending_[i];
    in.endstop_min = in_.endstop_min[i] != 0 ? 1 : 0;
    in.endstop_max = in_.endstop_max[i] != 0 ? 1 : 0;
    in.blocked = block_ != Block::None ? 1 : 0;
    // G15: a closed session is a lost link just like silence.
    in.link_alive = alive && session_open_ ? 1 : 0;
    const xy_axis::State before = axes_[i];
    const xy_axis::StepResult r = xy_axis::step(before, in, derived_.cfg[i]);
    axes_[i] = r.state;
    // This tick's command took effect unless the axis core refused it; a refused command
    // changed nothing and is its own echo, so it neither starts nor hides an event.
    const bool refused = in.cmd.kind != xy_axis::CmdKind::None && r.out.error != xy_axis::Error::None;
    const bool took = in.cmd.kind != xy_axis::CmdKind::None && !refused;
    if (refused) {
      refused_[i] = static_cast<std::uint8_t>(pending_id_[i]);
      ++counters_.refused_parts;
    } else if (in.cmd.kind == xy_axis::CmdKind::Stop) {
      // The echo shows the event that ended the last motion (docs/board.md "Echo content"):
      // a stop ends one only if the axis was moving or held a mode; at rest it changes
      // nothing, so a REACHED stays REACHED (docs/echo-model.md).
      if (moving(before) || before.mode != xy_axis::Mode::Idle) event_[i] = AxisEvent::StoppedByUser;
    } else if (took) {
      event_[i] = AxisEvent::None;  // an accepted motion command starts a new motion
    }
    const xy_axis::Edge edge = r.out.edge;
    if (edge == xy_axis::Edge::G || edge == xy_axis::Edge::H) {
      // Homing reached its reference only if the axis core took it (a stop in the same tick
      // ends the homing first: then it is a plain endstop stop; docs/echo-model.md).
      // The Home may also be this tick's command, given while moving down onto the switch.
      const bool homing = before.mode == xy_axis::Mode::Home || in.cmd.kind == xy_axis::CmdKind::Home;
      // A move whose carriage the switch halts on the move's own target reached what was
      // asked: REACHED is standing at the target, as for a stop in the tick of arrival
      // (docs/echo-model.md). The move is this tick's accepted goto / move, or the one held.
      const bool move = took ? (in.cmd.kind == xy_axis::CmdKind::MoveAbs || in.cmd.kind == xy_axis::CmdKind::MoveRel)
                             : before.mode == xy_axis::Mode::Position;
      const bool homed_here = homing && edge == xy_axis::Edge::G && r.state.homed != 0;
      const bool on_target = move && r.state.pos == r.state.target;
      event_[i] = homed_here || on_target ? AxisEvent::Reached : AxisEvent::Endstop;
    } else if (r.out.error == xy_axis::Error::HomeFailed) {
      event_[i] = AxisEvent::HomeFailed;
    } else if (before.mode == xy_axis::Mode::Jog && r.state.mode == xy_axis::Mode::Idle && in.link_alive == 0 &&
               in.cmd.kind == xy_axis::CmdKind::None) {
      event_[i] = AxisEvent::LinkLost;
    } else if (before.mode == xy_axis::Mode::Position && r.state.mode == xy_axis::Mode::Idle && r.state.pos == before.target &&
               !moving(r.state)) {
      // Reached means standing at the target: a stop that ends a move while the carriage
      // passes over its target still brakes beyond it, and stays STOPPED (docs/echo-model.md).
      event_[i] = AxisEvent::Reached;
    } else if (before.mode == xy_axis::Mode::Position && r.state.mode == xy_axis::Mode::Idle && !moving(before) &&
               !took && in.blocked == 0) {
      // A move standing short of its target (the reversal stop of a move that turned round)
      // whose way on is closed by an active or latched endstop: the axis core drops it (edge
      // I, motion.md §4), and the endstop is what ended it (docs/echo-model.md).
      event_[i] = AxisEvent::Endstop;
    } else if (r.state.mode == xy_axis::Mode::Position && !moving(r.state) && r.state.pos == r.state.target) {
      // Standing on the target of a move: the axis core halted there this tick (at or below
      // the start speed it may stop at once) and drops the finished move only on the next
      // tick (edge I), but the echo of this tick already describes a carriage standing at its
      // target: REACHED (docs/echo-model.md).
      event_[i] = AxisEvent::Reached;
    } else if ((in.cmd.kind == xy_axis::CmdKind::MoveAbs || in.cmd.kind == xy_axis::CmdKind::MoveRel) &&
               r.out.error == xy_axis::Error::None && r.state.mode == xy_axis::Mode::Idle && !moving(r.state) &&
               r.state.pos == r.state.target) {
      // A move to where the carriage already is: the requested position is reached
      // (docs/echo-model.md), not "standing, no target". Only there: a move the axis core
      // dropped in the same tick (a jog stopping hard at its soft limit) reached nothing.
      event_[i] = AxisEvent::Reached;
    } else if ((before.mode == xy_axis::Mode::Home || (in.cmd.kind == xy_axis::CmdKind::Home && r.out.error == xy_axis::Error::None)) &&
               r.state.mode == xy_axis::Mode::Idle && r.state.homed != 0 && !moving(r.state)) {
      // (A command of this tick the core refused does not hide a homing that completed.)
      // Homing that completes at standstill (switch already active, motion.md §6) is the same
      // completed reference as the G edge above: REACHED (docs/echo-model.md).
      event_[i] = AxisEvent::Reached;
    }
    // A completed reference makes where the carriage stands the axis's home position for good:
    // the absolute encoder is programmed so that it reads that position from now on, across
    // power cycles (thesis §7.7.2: the encoder's programmed zero is the absolute zero;
    // docs/motion.md "Homing and the encoder zero").
    const bool homing = before.mode == xy_axis::Mode::Home || in.cmd.kind == xy_axis::CmdKind::Home;
    if (homing && r.state.mode != xy_axis::Mode::Home && event_[i] == AxisEvent::Reached && hw_.encoder_zero != nullptr) {
      hw_.encoder_zero(hw_.ctx, static_cast<Axis>(i), encoder_counts_at(r.state.pos));
    }
    edge_[i] = r.out.edge;
    error_[i] = r.out.error;
    MotorOutput& m = motor_[i];
    m.dir = r.out.dir;
    m.steps = r.out.steps;
    m.step_hz = static_cast<std::uint32_t>(r.out.step_speed / xy_axis::kSpeedScale);
    // G24: asleep, the drivers are switched off once the carriage stands; blocked they keep
    // their hold current so the platform cannot be pushed off its counted position.
    m.enable = !(sleeping_ && !moving(r.state) && r.out.steps == 0);
    if (hw_.motor != nullptr) hw_.motor(hw_.ctx, static_cast<Axis>(i), m);
  }
}

std::int64_t Board::encoder_counts_at(std::int32_t pos) const {
  return xy_axis::encoder_counts_for(pos, static_cast<std::int32_t>(xy_axis::usteps_per_rev(derived_.mech)));
}

}  // namespace ap::xy_board
