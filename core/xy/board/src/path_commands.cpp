// The board's side of the coordinated path (docs/cnc.md "On the board"): the path commands'
// handlers, the segment a frame's two parts make, and the tick that drives both axes from the
// path executor instead of the axis core.
#include <algorithm>

#include "core/xy/board/board.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "helpers.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
using xy_frame::HandlerStatus;

namespace {

// The thesis's jerk limit, J = 20 mm/s^3 (seed-003.md §5.3.1), in micrometres: the platform's
// path jerk. A stored parameter would change the FRAM map; docs/cnc.md "Speeds" has why not.
constexpr std::int32_t kPathJerkUmS3 = 20'000;

bool is_segment(c::CommandId id) {
  return id == c::CommandId::PathLine || id == c::CommandId::PathArcCw || id == c::CommandId::PathArcCcw;
}

xy_axis::Phase phase_of(std::uint8_t profile_segment, bool stopping) {
  if (stopping) return xy_axis::Phase::Decel;
  if (profile_segment < 3) return xy_axis::Phase::Accel;
  if (profile_segment == 3) return xy_axis::Phase::Const;
  return xy_axis::Phase::Decel;
}

}  // namespace

xy_path::Limits Board::path_limits() const {
  xy_path::Limits lim;
  const xy_axis::Config& x = derived_.cfg[0];
  const xy_axis::Config& y = derived_.cfg[1];
  // One profile moves both axes, so the slower axis's speed and acceleration bound the path.
  lim.motion.v_max = std::min({x.v_fast, y.v_fast, xy_scurve::kMaxVelocity});
  lim.motion.a_max = std::min(x.accel, y.accel);
  const xy_axis::Converted j = xy_axis::um_to_usteps(kPathJerkUmS3, derived_.mech, xy_axis::Round::Nearest);
  lim.motion.j_max = std::max<std::int32_t>(j.value, 1);
  lim.soft_min = {x.soft_min, y.soft_min};
  lim.soft_max = {x.soft_max, y.soft_max};
  return lim;
}

HandlerStatus Board::path_part(Axis a, c::CommandId id, std::int32_t um) {
  const std::size_t i = idx(a);
  path_id_[i] = id;
  path_um_[i] = um;
  return HandlerStatus::Done;
}

HandlerStatus Board::on_path_end(void* ctx, Axis, std::int32_t) {
  static_cast<Board*>(ctx)->path_.close();
  return HandlerStatus::Done;
}

// After a frame's dispatch: its path parts become the next arc's centre or one segment.
void Board::commit_path_frame(const xy_frame::CommandFrame& f) {
  const std::array<c::CommandId, kAxes> ids = path_id_;
  path_id_ = {c::CommandId::Nop, c::CommandId::Nop};
  const auto refuse_parts = [&](xy_path::Error e) {
    path_error_ = e;
    for (std::size_t i = 0; i < kAxes; ++i) {
      if (ids[i] == c::CommandId::Nop) continue;
      refused_[i] = static_cast<std::uint8_t>(ids[i]);
      ++counters_.refused_parts;
    }
  };
  const bool centre = ids[0] == c::CommandId::PathCentre || ids[1] == c::CommandId::PathCentre;
  const bool segment = is_segment(ids[0]) || is_segment(ids[1]);
  if (!centre && !segment) return;
  if (centre && segment) return refuse_parts(xy_path::Error::MixedParts);  // one frame, one meaning
  // A segment beside an axis's own motion command (or a stop) would leave one of the two
  // unanswered: the frame is refused as mixed, the other part runs as it would alone.
  for (const xy_frame::AxisCommand* part : {&f.x, &f.y}) {
    const c::CommandId id = part->id;
    if (segment && (id == c::CommandId::Stop || id == c::CommandId::Jog || id == c::CommandId::Goto ||
                    id == c::CommandId::Move || id == c::CommandId::GotoSlow || id == c::CommandId::MoveSlow ||
                    id == c::CommandId::Home)) {
      return refuse_parts(xy_path::Error::MixedParts);
    }
  }
  if (centre) {
    // Both parts carry the centre's absolute coordinates (docs/cnc.md).
    if (ids[0] != c::CommandId::PathCentre || ids[1] != c::CommandId::PathCentre) return refuse_parts(xy_path::Error::MixedParts);
    centre_um_ = path_um_;
    centre_set_ = true;
    return;
  }
  c::CommandId kind = c::CommandId::Nop;
  for (std::size_t i = 0; i < kAxes; ++i) {
    if (!is_segment(ids[i])) continue;
    if (kind != c::CommandId::Nop && ids[i] != kind) return refuse_parts(xy_path::Error::MixedParts);
    kind = ids[i];
  }
  // What every motion command needs: awake, the position known, no axis moving on its own or
  // holding a motion (holds_motion: a move standing on its target is finished).
  bool busy = false;
  for (std::size_t i = 0; i < kAxes; ++i) {
    if (axes_[i].homed == 0) return refuse_parts(xy_path::Error::NotHomed);
    if (!path_.active() && holds_motion(axes_[i])) busy = true;
    // A motion command taken earlier in this tick is stored, not yet applied: the segment would
    // silently replace it, so the segment is the one refused.
    const xy_axis::CmdKind k = pending_[i].kind;
    if (k == xy_axis::CmdKind::Jog || k == xy_axis::CmdKind::MoveAbs || k == xy_axis::CmdKind::MoveRel || k == xy_axis::CmdKind::Home) busy = true;
  }
  if (busy || sleeping_) return refuse_parts(xy_path::Error::Busy);
  xy_path::Segment s;
  s.kind = kind == c::CommandId::PathLine ? xy_path::Kind::Line
                                         : (kind == c::CommandId::PathArcCw ? xy_path::Kind::ArcCw : xy_path::Kind::ArcCcw);
  s.start = path_.queued() > 0 ? path_.queue_end() : xy_path::Point{axes_[0].pos, axes_[1].pos};
  s.end = s.start;
  for (std::size_t i = 0; i < kAxes; ++i) {
    if (ids[i] != kind) continue;
    const xy_axis::Converted t = xy_axis::um_to_usteps(path_um_[i], derived_.mech, xy_axis::Round::Nearest);
    if (t.error != xy_axis::Error::None) return refuse_parts(xy_path::Error::OutOfLimits);
    s.end[i] = t.value;
  }
  if (s.kind != xy_path::Kind::Line) {
    if (!centre_set_) return refuse_parts(xy_path::Error::NoCentre);
    for (std::size_t i = 0; i < kAxes; ++i) {
      const xy_axis::Converted o = xy_axis::um_to_usteps(centre_um_[i], derived_.mech, xy_axis::Round::Nearest);
      if (o.error != xy_axis::Error::None) return refuse_parts(xy_path::Error::OutOfLimits);
      s.centre[i] = o.value;
    }
  }
  const xy_path::Error e = path_.add(s, path_limits());
  if (e != xy_path::Error::None) return refuse_parts(e);
  if (s.kind != xy_path::Kind::Line) centre_set_ = false;
  // The saved step counter stops being valid before the first step (as for every motion).
  if (!motion_permitted()) {
    path_.clear();
    return refuse_parts(xy_path::Error::Busy);
  }
  for (std::size_t i = 0; i < kAxes; ++i) event_[i] = AxisEvent::None;
}

// A user's stop (`stop` of either axis, sleep): a running path brakes along its S-curve, a
// standing one drops its queue at once (xy_path::Executor::stop). The first cause names the end.
void Board::stop_path_by_user() {
  if (!path_.stopping()) path_stop_event_ = AxisEvent::StoppedByUser;
  path_.stop();
}

void Board::step_path(bool alive) {
  // A lost link, a closed session, a block or sleep stop the path along its own S-curve: a
  // controlled stop (docs/cnc.md "Stops"), as the axis core brakes a jog.
  if (!path_.stopping()) {
    if (!alive || !session_open_) {
      path_stop_event_ = AxisEvent::LinkLost;
      path_.stop();
    } else if (block_ != Block::None || sleeping_) {
      stop_path_by_user();
    }
  }
  xy_path::TickIn ti;
  for (std::size_t i = 0; i < kAxes; ++i) {
    ti.toward_min_blocked[i] = in_.endstop_min[i] != 0 || axes_[i].latch_min != 0;
    ti.toward_max_blocked[i] = in_.endstop_max[i] != 0 || axes_[i].latch_max != 0;
  }
  const bool was_stopping = path_.stopping();
  xy_path::Point pos{axes_[0].pos, axes_[1].pos};
  xy_path::Halt halt = xy_path::Halt::None;
  const xy_path::TickOut o = path_.tick(ti, pos, halt);
  for (std::size_t i = 0; i < kAxes; ++i) {
    xy_axis::State& s = axes_[i];
    s.pos = pos[i];
    s.dir = o.dir[i];
    s.v = halt != xy_path::Halt::None ? 0 : o.v_fine[i];
    s.phase = s.v > 0 ? phase_of(path_.profile_segment(), path_.stopping()) : xy_axis::Phase::Stop;
    s.mode = xy_axis::Mode::Idle;
    s.target = s.pos;
    s.frac = 0;
    // The endstop latches as the axis core keeps them (motion.md §4): set by the switch, cleared
    // by a step away from it with the switch off.
    if (in_.endstop_min[i] != 0) s.latch_min = 1;
    if (in_.endstop_max[i] != 0) s.latch_max = 1;
    if (o.steps[i] > 0 && o.dir[i] > 0 && in_.endstop_min[i] == 0) s.latch_min = 0;
    if (o.steps[i] > 0 && o.dir[i] < 0 && in_.endstop_max[i] == 0) s.latch_max = 0;
    MotorOutput& m = motor_[i];
    m.dir = o.dir[i];
    m.steps = o.steps[i];
    m.step_hz = static_cast<std::uint32_t>(s.v / xy_axis::kSpeedScale);
    m.enable = true;
    if (hw_.motor != nullptr) hw_.motor(hw_.ctx, static_cast<Axis>(i), m);
    if (halt == xy_path::Halt::Endstop) {
      event_[i] = AxisEvent::Endstop;
    } else if (o.finished_chain && !path_.active()) {
      event_[i] = was_stopping ? path_stop_event_ : AxisEvent::Reached;
    }
  }
  if (!path_.active()) path_stop_event_ = AxisEvent::None;
}

}  // namespace ap::xy_board
