#include "models/xy/safety/board_monitor.hpp"

#include <algorithm>

#include "core/xy/axis/watchdog.hpp"

namespace ap::model::xy_safety {

namespace {

bool same_mechanics(const xy_axis::Mechanics& a, const xy_axis::Mechanics& b) {
  return a.pitch_um == b.pitch_um && a.steps_per_rev == b.steps_per_rev && a.microsteps == b.microsteps;
}

// Frames that feed the link watchdog: run, or a repeat of the last one taken.
std::uint32_t fed(const xy_board::Board& b) { return b.counters().dispatched_frames + b.counters().repeated_frames; }

}  // namespace

void BoardMonitor::booted(const xy_board::Board& b) {
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    w_[a] = AxisWatch{};
    w_[a].latch_min = b.inputs().endstop_min[a] != 0;
    w_[a].latch_max = b.inputs().endstop_max[a] != 0;
  }
  silent_ = xy_axis::kLinkTimeoutTicks;
  fed_ = fed(b);
}

void BoardMonitor::before_tick(const xy_board::Board& b) {
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) before_[a] = b.axis_state(static_cast<xy_board::Axis>(a));
  mech_ = b.mechanics();
  path_active_ = b.path().active();
  path_stopping_ = b.path().stopping();
  path_vel_ = b.path().kinematics().vel_milli;
  path_acc_ = b.path().kinematics().accel_milli;
  if (b.path().queued() > 0) path_end_ = b.path().queue_end();
}

void BoardMonitor::check_path(const xy_board::Board& b, std::vector<Violation>& out) {
  const std::uint32_t t = b.ticks();
  const xy_path::Executor& p = b.path();
  if (!path_active_ && !p.active()) return;
  // The move rate is at most v_max (the slower axis's fast speed): v_max / 1000 moves per tick,
  // one more for the floor of the profile's position, and a tick may also make the moves a
  // reversal held back from the tick before (docs/cnc.md "Axis speeds").
  const std::int64_t v_max = std::min<std::int64_t>(b.axis_config(xy_board::Axis::X).v_fast, b.axis_config(xy_board::Axis::Y).v_fast);
  const std::int64_t per_tick = 2 * (v_max / 1000 + 1);
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    if (b.motor_output(static_cast<xy_board::Axis>(a)).steps > per_tick) {
      out.push_back({t, static_cast<int>(a), "path steps faster than its v_max"});
    }
  }
  // A jerk-limited stop first ramps a positive acceleration down to zero (the thesis's rule:
  // deceleration starts at a = 0, seed-003.md §9); from then on the speed never rises.
  if (path_stopping_ && p.active() && path_acc_ <= 0 && p.kinematics().vel_milli > path_vel_) {
    out.push_back({t, -1, "path speed rose during a controlled stop"});
  }
  if (path_active_ && !p.active() && !path_stopping_) {
    bool reached = true;
    for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
      reached = reached && b.axis_event(static_cast<xy_board::Axis>(a)) == xy_board::AxisEvent::Reached;
    }
    for (std::size_t a = 0; reached && a < xy_board::kAxes; ++a) {
      if (b.axis_state(static_cast<xy_board::Axis>(a)).pos != path_end_[a]) {
        out.push_back({t, static_cast<int>(a), "path ended away from its last segment's end"});
      }
    }
  }
}

void BoardMonitor::after_tick(const xy_board::Board& b, std::vector<Violation>& out) {
  const std::uint32_t f = fed(b);
  silent_ = f != fed_ ? 0 : silent_ + 1;
  fed_ = f;
  const bool mech_changed = !same_mechanics(b.mechanics(), mech_);
  bool any_steps = false;
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    check_axis(b, a, mech_changed, out);
    any_steps = any_steps || b.motor_output(static_cast<xy_board::Axis>(a)).steps > 0;
  }
  check_path(b, out);
  // The saved step counter is never marked valid while the carriage moves.
  if (any_steps && b.store().current().step_counts_valid) out.push_back({b.ticks(), -1, "step while the saved counter is valid"});
}

void BoardMonitor::check_axis(const xy_board::Board& b, std::size_t a, bool mech_changed, std::vector<Violation>& out) {
  const auto ax = static_cast<xy_board::Axis>(a);
  const int ai = static_cast<int>(a);
  const std::uint32_t t = b.ticks();
  const xy_axis::State& p = before_[a];
  const xy_axis::State& n = b.axis_state(ax);
  const xy_axis::Config& c = b.axis_config(ax);
  const xy_board::MotorOutput& o = b.motor_output(ax);
  const xy_board::Inputs& in = b.inputs();
  AxisWatch& x = w_[a];
  auto bad = [&](const char* what) { out.push_back({t, ai, what}); };
  if (!xy_axis::state_valid(n)) bad("axis state out of its invariant ranges");
  // DIR changes only at or below the start speed (a reversal decelerates first).
  if (n.dir != p.dir && p.v > c.v_start * xy_axis::kSpeedScale) bad("DIR flipped above the start speed");
  if (o.steps > 0 && o.dir != n.dir) bad("steps emitted against the DIR state");
  // No step toward an active endstop, nor toward one not yet moved away from.
  if (in.endstop_min[a] != 0) x.latch_min = true;
  if (in.endstop_max[a] != 0) x.latch_max = true;
  if (o.steps > 0) {
    if (o.dir < 0 && x.latch_min) bad("step toward an active min endstop");
    if (o.dir > 0 && x.latch_max) bad("step toward an active max endstop");
    if (o.dir > 0 && in.endstop_min[a] == 0) x.latch_min = false;
    if (o.dir < 0 && in.endstop_max[a] == 0) x.latch_max = false;
  }
  // Blocked: brake only; once stopped, not one step until unblocked.
  if (b.block() == xy_board::Block::None) {
    x.blocked_stopped = false;
  } else {
    // On an arc one axis's share of the path speed can grow while the path brakes: there the
    // path's own speed is what must not rise (check_path).
    if (n.v > p.v && !path_active_) bad("speed increased while blocked");
    if (x.blocked_stopped && (o.steps != 0 || n.v != 0)) bad("step while blocked after the stop");
    // A braking path stops both axes together: an axis whose share of the path speed passes 0
    // on an arc has not stopped (docs/cnc.md "Axis speeds").
    x.blocked_stopped = x.blocked_stopped || (n.v == 0 && !b.path().active());
  }
  if (mech_changed) {
    x.tracking = false;
    return;
  }
  // Soft limits are never crossed once the position is known.
  if (p.homed != 0 && n.homed != 0 && p.pos >= c.soft_min && p.pos <= c.soft_max &&
      (n.pos < c.soft_min || n.pos > c.soft_max)) {
    bad("soft travel limit crossed");
  }
  // The link watchdog: no jog outlives 3 silent command periods.
  if (silent_ >= xy_axis::kLinkTimeoutTicks && n.mode == xy_axis::Mode::Jog) bad("jog still running after the link watchdog period");
  // A target set from rest is reachable: it must never be passed.
  const bool new_move = n.mode == xy_axis::Mode::Position && (p.mode != xy_axis::Mode::Position || p.target != n.target);
  if (new_move) {
    x.tracking = p.v == 0;
    x.target = n.target;
    x.side = p.pos > n.target ? 1 : (p.pos < n.target ? -1 : 0);
  }
  if (!x.tracking) return;
  // A counter that moved by more than the tick's steps was re-referenced, not driven: Home
  // given as the carriage runs onto the min switch takes the reference there (motion.md §6,
  // G19; docs/echo-model.md "Decisions"), and the jump to 0 passes no target on the table.
  const std::int64_t moved = static_cast<std::int64_t>(n.pos) - p.pos;
  if ((moved < 0 ? -moved : moved) > static_cast<std::int64_t>(o.steps)) {
    x.tracking = false;
    return;
  }
  const int side = n.pos > x.target ? 1 : (n.pos < x.target ? -1 : 0);
  if (side != 0 && x.side != 0 && side != x.side) bad("reachable target passed");
  if (side != 0) x.side = side;
  if (n.mode != xy_axis::Mode::Position || n.target != x.target) x.tracking = false;
}

}  // namespace ap::model::xy_safety
