// After the axes stepped (docs/board.md "One cycle (tick) in order" steps 4-8): the link
// watchdog (G15, docs/motion.md §7), the endstop latches (motion.md §4), the event that ended
// each axis's motion, read from the observed phase and step counter (REACHED, STOPPED, ENDSTOP,
// LINK_LOST, homing: motion.md §6; docs/board.md G16 while blocked; the decisions in
// docs/echo-model.md "Decisions"), then the path's progress (path.cpp), the sensors
// (sensors.cpp), what became of the frame taken (docs/protocol.md "Delivery", "Outcomes") and
// the tick's echoes (echo_content.cpp). Observed motion the model forbids is recorded here as a
// violation.
#include "models/xy/echo/echo_model.hpp"

#include <cstdint>
#include <string>

namespace ap::model::xy_echo {
namespace {

using xy_codec::EchoStatus;

// docs/motion.md §7: alive while fewer than 300 ticks passed since the last dispatched frame.
constexpr std::uint32_t kWatchdogTicks = 300;

}  // namespace

// ---------------------------------------------------------------- after the axes stepped
std::span<const Expected> EchoModel::end_tick(const Motion& motion) {
  // G15: a jog needs a dispatched frame within the last 300 ticks and an open session.
  const bool alive = session_ && since_dispatch_ < kWatchdogTicks;
  if (since_dispatch_ < 0xFFFFFFFFU) ++since_dispatch_;
  // cnc.md "Stops": a lost link or a closed session stops the path (unlike a move).
  if (!alive) path_request_stop(PathStop::Link);
  std::array<bool, kAxes> halted_on_switch{};
  for (std::size_t a = 0; a < kAxes; ++a) {
    Ax& x = ax_[a];
    const AxisMotion& m = motion[a];
    const AxisMotion prev = x.last;
    const bool moving = m.phase != Phase::Stop;
    const bool was_moving = prev.phase != Phase::Stop;
    if (x.act == Activity::Jog && !alive) {
      x.act = Activity::Braking;
      x.stop_requested = false;  // the link ended it, not the user
      x.ended = Ended::None;
      x.jog_dir = 0;
      x.link_ended = true;
    }
    // Endstop latches (motion.md §4): set while the input is active, cleared by a step away
    // with the input released.
    if (env_.endstop_min[a]) x.latch_min = true;
    else if (x.latch_min && m.steps > 0 && m.dir > 0) x.latch_min = false;
    if (env_.endstop_max[a]) x.latch_max = true;
    else if (x.latch_max && m.steps > 0 && m.dir < 0) x.latch_max = false;

    const bool at_min = env_.endstop_min[a], at_max = env_.endstop_max[a];
    const bool endstop_in_dir = (prev.dir < 0 && at_min) || (prev.dir > 0 && at_max);
    // Halted, not come to rest: it stepped in its last tick, or it stands straight from ACCEL
    // or CONST (a controlled stop ends in DECEL), its way on closed by an active or latched
    // switch (motion_allowed, motion.md §4).
    halted_on_switch[a] = was_moving && (prev.steps > 0 || prev.phase != Phase::Decel) && !moving &&
                          !motion_allowed(a, prev.dir);

    if (block_ != EchoStatus::Idle) {
      // A path chain whose S-curve had begun when the block came brakes along it (cnc.md
      // "Stops"), and its first braking tick may be the first to show motion, as for a user
      // stop (fuzz/regressions/board/block-of-a-chain-before-its-first-step).
      const bool chain_braking = path_.running && path_.chain_running;
      if (moving && !was_moving && !chain_braking) {
        violations_.push_back("axis " + std::string(a == 0 ? "x" : "y") + " started while blocked");
      }
      // The event that ended the last motion stands until G16 clears it at the block's end;
      // the answer to a repeat shows it meanwhile (docs/protocol.md "What a repeat answers").
      // The braking under the block may end on a switch, or, in the block's first tick, on the
      // move's own target (block entry above).
      if (!moving && x.act != Activity::Idle) {
        if (was_moving && endstop_in_dir) x.ended = Ended::Endstop;
        else if (x.stopped_move_now && m.pos == x.target) x.ended = Ended::Reached;
        x.act = Activity::Idle;
      }
      x.last = m;
      continue;
    }
    if (moving) {
      if (x.act == Activity::Idle && !was_moving && !path_.running) {
        violations_.push_back("axis " + std::string(a == 0 ? "x" : "y") + " started at tick " + std::to_string(ticks_) +
                              " with no accepted motion command");
      }
      x.last = m;
      continue;
    }
    // Standing after this tick.
    switch (x.act) {
      case Activity::Idle: break;
      case Activity::Jog:
        if (was_moving && endstop_in_dir) {  // G/H: an endstop ends the jog
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        }
        // Otherwise a reversal (E then A next tick) or the jog braked onto its soft limit:
        // the jog is still held.
        break;
      case Activity::Position:
        if (m.pos == x.target) {
          x.act = Activity::Idle;
          x.ended = Ended::Reached;
        } else if (was_moving && endstop_in_dir) {
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        } else if (!was_moving && !motion_allowed(a, m.pos < x.target ? 1 : -1)) {
          // Standing short of the target (the reversal stop of a move that turned round) with
          // the switch toward the target active or latched: motion.md §4 refuses motion toward
          // it, so the endstop ended the move (docs/echo-model.md "Decisions").
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        }
        break;
      case Activity::Home:
        if (was_moving && prev.dir > 0 && at_max) {  // braking upward into the max switch: H
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        } else if (was_moving && prev.dir > 0) {
          // The reversal stop of a Home issued while moving up: still homing. motion.md §6
          // takes the reference "at standstill", i.e. from the next tick on, also when the
          // min switch is already active (docs/echo-model.md "Decisions").
        } else if (at_min || (!was_moving && x.latch_min)) {
          // G19: the min endstop is the reference point; at standstill a latched switch counts
          // as active (motion.md §4).
          x.act = Activity::Idle;
          x.homed = true;
          x.ended = Ended::Reached;  // the reference position is reached (decision)
        } else if (was_moving && prev.dir < 0) {  // travelled toward min without a switch
          x.act = Activity::Idle;
          x.ended = Ended::HomeFailed;
        }
        break;
      case Activity::Braking:
        x.act = Activity::Idle;
        if (was_moving && endstop_in_dir) x.ended = Ended::Endstop;
        // A stop given in the very tick a move comes to rest on its target ended nothing the
        // move did not end itself: REACHED (docs/echo-model.md "Decisions").
        else if (x.stopped_move_now && m.pos == x.target) x.ended = Ended::Reached;
        else if (x.stop_requested) x.ended = Ended::Stopped;
        else if (x.link_ended) x.ended = Ended::LinkLost;
        x.stop_requested = false;
        x.link_ended = false;
        break;
    }
    x.last = m;
  }
  path_end_tick(motion, halted_on_switch);
  sensors_tick();
  if (taken_this_tick_) {
    last_block_ = block_;
    for (std::size_t a = 0; a < kAxes; ++a) last_refused_[a] = ax_[a].refused;
    fate_ = FrameFate{taken_frame_, block_ != EchoStatus::Idle, last_refused_};
  }
  for (std::size_t i = 0; i < events_.size(); ++i) out_.push_back(build(i));
  return out_;
}

std::vector<std::string> EchoModel::take_violations() {
  std::vector<std::string> v;
  v.swap(violations_);
  return v;
}

}  // namespace ap::model::xy_echo
