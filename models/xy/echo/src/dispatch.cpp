// A frame event and the command handlers (echo_model.hpp's frame()): the session gate and the
// link layer's verdict (docs/board.md "One cycle (tick) in order" step 3, G15), the callback
// table's checks (docs/protocol.md "Dispatch: the callback table"), the window that tells a
// new frame from a repeat or an older one (docs/protocol.md "Delivery"), a frame taken while
// blocked (§7.5.2), then each axis part's handler: what it starts, refuses or stops, and a
// command stored earlier in the same cycle that it replaces unseen (docs/motion.md §4, §6, §7;
// docs/board.md "One cycle (tick) in order", G20, G24; docs/echo-model.md "Decisions"). A
// parameter command's verdict is parameters.cpp's, a path frame's is path.cpp's.
#include "models/xy/echo/echo_model.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include "protocol/xy/codec/errors.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::model::xy_echo {
namespace {

using xy_codec::CommandId;
using xy_codec::EchoStatus;
using xy_codec::FrameError;

}  // namespace

// ---------------------------------------------------------------- receive (§7.5.1 step 3)
std::optional<xy_frame::Rejection> EchoModel::table_check(const xy_frame::CommandFrame& f) const {
  // docs/protocol.md "Dispatch": per axis part in wire order: ID against the table, then the
  // data against that command's range; then the subscriber slots. Offsets: ID_X 4, Data_X 6,
  // ID_Y 12, Data_Y 14, slot k ID 20 + 4k, argument 22 + 4k (the frame layout table).
  const std::array<std::pair<const xy_frame::AxisCommand*, std::uint16_t>, 2> parts{{{&f.x, 4}, {&f.y, 12}}};
  for (const auto& [part, off] : parts) {
    const auto id = static_cast<std::uint32_t>(part->id);
    if (id >= xy_codec::kCommands.size()) return xy_frame::Rejection{FrameError::UnknownCommand, off};
    if (!xy_codec::kCommands[id].range.contains(part->data)) {
      return xy_frame::Rejection{FrameError::DataOutOfRange, static_cast<std::uint16_t>(off + 2)};
    }
  }
  for (std::size_t k = 0; k < f.subs.size(); ++k) {
    const auto id = static_cast<std::uint32_t>(f.subs[k].id);
    const auto off = static_cast<std::uint16_t>(20 + 4 * k);
    const auto* info = xy_codec::find_subscriber(id);
    if (info == nullptr) return xy_frame::Rejection{FrameError::UnknownSubscriber, off};
    if (!info->arg_range.contains(f.subs[k].arg)) {
      return xy_frame::Rejection{FrameError::ArgOutOfRange, static_cast<std::uint16_t>(off + 2)};
    }
  }
  return std::nullopt;
}

void EchoModel::frame(const FrameEvent& ev) {
  Pending p;
  // G15 (docs/board.md): frames in any state but Data Session open are dropped without an
  // echo, damaged ones included.
  if (!session_) return;
  if (!ev.link.ok()) {  // the link layer rejected it: answered, nothing else (protocol.md)
    p.rejected = true;
    p.rejection = ev.link;
    p.frame.seq = last_seq_;  // the last accepted seq at this event (protocol.md)
    events_.push_back(p);
    return;
  }
  if (const auto r = table_check(ev.frame)) {
    p.rejected = true;
    p.rejection = *r;
    p.frame.seq = last_seq_;
    events_.push_back(p);
    return;
  }
  p.frame = ev.frame;
  // protocol.md "Delivery": a seq 1..499 ahead of the last one taken (mod 1000) is new, the
  // same seq is a repeat, 500..999 ahead is older; the first frame after power-up is new.
  // Neither a repeat nor an older frame runs; both are answered with the seq of the last frame
  // taken and its outcome (refusals, block); a repeat feeds the watchdog unless blocked.
  const int ahead = (static_cast<int>(ev.frame.seq) - static_cast<int>(last_seq_) + 1000) % 1000;
  if (have_seq_ && (ahead == 0 || ahead >= 500)) {
    p.replay = true;
    p.frame.seq = last_seq_;
    if (ahead == 0 && block_ == EchoStatus::Idle) {
      since_dispatch_ = 0;
      dispatched_this_tick_ = true;
    }
    events_.push_back(p);
    return;
  }
  have_seq_ = true;
  last_seq_ = ev.frame.seq;
  taken_this_tick_ = true;
  taken_frame_ = ev.frame;
  if (block_ != EchoStatus::Idle) {  // §7.5.2: commands cannot act while blocked; answered
    p.blocked = true;
    events_.push_back(p);
    return;
  }
  // Dispatched: X handler then Y handler; the watchdog is refreshed (G15).
  dispatch(xy_frame::Axis::X, ev.frame.x.id, ev.frame.x.data);
  dispatch(xy_frame::Axis::Y, ev.frame.y.id, ev.frame.y.data);
  // docs/cnc.md "From G-code to the axes" 2: the path parts of one frame are one segment,
  // checked and queued once both parts are handled.
  path_frame(ev.frame);
  since_dispatch_ = 0;
  dispatched_this_tick_ = true;
  events_.push_back(p);
}

void EchoModel::refuse(std::size_t a, CommandId id, const char*) { ax_[a].refused = id; }

bool EchoModel::motion_allowed(std::size_t a, std::int8_t dir) const {
  // motion.md §4 (G8): refused toward an endstop whose input is active or whose latch is set.
  const Ax& x = ax_[a];
  if (dir > 0) return !(env_.endstop_max[a] || x.latch_max);
  if (dir < 0) return !(env_.endstop_min[a] || x.latch_min);
  return true;
}

void EchoModel::supersede(std::size_t a) {
  // docs/board.md "One cycle": the handlers only store the command; the axis core applies
  // the last one of the cycle when the axes step. A motion command accepted earlier in this
  // tick and replaced now never reached the axis: no motion started, none ended, homing did
  // not clear the known position (docs/echo-model.md "Decisions"). Its refusal, if any, stays.
  Ax& x = ax_[a];
  if (!x.started_now) return;
  const auto refused = x.refused;
  x = at_tick_start_[a];
  x.refused = refused;
}

void EchoModel::dispatch(xy_frame::Axis axis, CommandId id, std::int32_t d) {
  const auto a = static_cast<std::size_t>(axis);
  Ax& x = ax_[a];
  const auto start = [&](Activity act) {
    supersede(a);
    x.act = act;
    x.ended = Ended::None;
    x.stop_requested = false;
    x.link_ended = false;
    x.started_now = true;
  };
  switch (id) {
    case CommandId::Nop: return;
    case CommandId::Stop:
    stop:
      // motion.md §6: a ramped stop, always accepted. cnc.md "Stops": either axis's stop
      // stops the path (a controlled stop along it).
      path_request_stop(PathStop::User);
      supersede(a);
      if (x.act != Activity::Idle) {
        x.stopped_move_now = x.act == Activity::Position;
        x.act = Activity::Braking;
        x.stop_requested = true;
      }
      return;
    case CommandId::Jog: {
      // cnc.md "Refusals": `jog` is refused while a path is active, its release (data 0) too
      // (docs/echo-model.md "The coordinated path").
      if (path_.running) return refuse(a, id, "a path is active");
      if (d == 0) goto stop;  // G20: key released = ramped stop
      const std::int8_t dir = d > 0 ? 1 : -1;
      if (sleeping_) return refuse(a, id, "sleeping");  // board.md G24
      if (!motion_allowed(a, dir)) return refuse(a, id, "toward an endstop");
      start(Activity::Jog);
      x.jog_dir = dir;
      return;
    }
    case CommandId::Goto:
    case CommandId::GotoSlow:
    case CommandId::Move:
    case CommandId::MoveSlow: {
      if (sleeping_) return refuse(a, id, "sleeping");
      if (path_.running) return refuse(a, id, "a path is active");  // cnc.md "Refusals"
      if (!x.homed) return refuse(a, id, "position unknown");  // motion.md §6
      std::int64_t target = 0;
      if (id == CommandId::Goto || id == CommandId::GotoSlow) {
        // motion.md §7 and §10: outside the um limits is refused; the rounded target is
        // pulled back onto an inward-rounded limit.
        if (d < p_.soft_min[a] || d > p_.soft_max[a]) return refuse(a, id, "outside the soft limits");
        target = to_usteps(d);
        if (target < limit_min(a)) target = limit_min(a);
        if (target > limit_max(a)) target = limit_max(a);
      } else {
        // motion.md §6: PP = AP + delta, checked against the limits like an absolute target.
        target = static_cast<std::int64_t>(x.last.pos) + to_usteps(d);
        if (target < limit_min(a) || target > limit_max(a)) return refuse(a, id, "outside the soft limits");
      }
      const std::int8_t dir = target > x.last.pos ? 1 : target < x.last.pos ? -1 : 0;
      if (!motion_allowed(a, dir)) return refuse(a, id, "toward an endstop");
      start(Activity::Position);
      x.target = static_cast<std::int32_t>(target);
      return;
    }
    case CommandId::Home:
      if (sleeping_) return refuse(a, id, "sleeping");
      if (path_.running) return refuse(a, id, "a path is active");  // cnc.md "Refusals"
      if (p_.homing_mode != 1) return refuse(a, id, "homing mode not 1");  // docs/storage.md
      start(Activity::Home);
      if (x.last.phase == Phase::Stop && (env_.endstop_min[a] || x.latch_min)) {
        // motion.md §6: resting on the (active or latched) min switch is the reference point.
        x.act = Activity::Idle;
        x.homed = true;
        x.ended = Ended::Reached;
        return;
      }
      x.homed = false;  // motion.md §6: homing clears the known position
      return;
    case CommandId::SetFastSpeed:
    case CommandId::SetSlowSpeed:
    case CommandId::SetAccel:
    case CommandId::SetStartSpeed:
    case CommandId::SetPitch:
    case CommandId::SetSteps:
    case CommandId::SetMicrosteps:
    case CommandId::SetIrun:
    case CommandId::SetIhold: {
      std::string why;
      if (!set_param(id, d, why)) refuse(a, id, "parameter");
      return;
    }
    case CommandId::PeriphOff:
      sleep_all();
      return;
    case CommandId::PeriphOn: sleeping_ = false; return;
    case CommandId::SaveParams: return;
    case CommandId::ClearFault: fault_ = 0; return;
    case CommandId::PathLine:
    case CommandId::PathCentre:
    case CommandId::PathArcCw:
    case CommandId::PathArcCcw:
    case CommandId::PathEnd: return;  // path_frame(), once both parts are handled
  }
}

}  // namespace ap::model::xy_echo
