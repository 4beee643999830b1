// The step function, step(): one control tick of one axis, straight-line code over the POD
// structs of axis.hpp (docs/motion.md §3 "Structure of step(state, input, config)"): the
// command applied (§6 "Modes", §8 "Bad input"), the goal, the tick classified, the speed law
// with the stop at the target (§5, G9) and the transition (§4). It stays one file, with the
// helpers only it calls, because the proofs mirror it line for line
// (models/xy/smt/axis_encoding.hpp). What it reads from elsewhere: the transition table
// (table.cpp) and the braking kernels (kernels.cpp), which the proofs mirror on their own.
#include "core/xy/axis/axis.hpp"

#include <limits>

#include "kernels.hpp"

namespace ap::xy_axis {
namespace {

constexpr int64_t kDist = kDistScale;

int32_t level_speed(const Config& c, uint8_t level) { return level != 0 ? c.v_fast : c.v_slow; }

// The hard bound in direction d: soft limits only mean something once the position is known;
// before that the step counter's own range is the only bound (endstops protect the hardware).
int32_t hard_bound(const State& s, const Config& c, int8_t d) {
  if (d > 0) {
    return s.homed != 0 ? c.soft_max : kPosMax;
  }
  return s.homed != 0 ? c.soft_min : -kPosMax;
}

bool endstop_active(const State& s, const Input& in, int8_t d) {
  return d > 0 ? (in.endstop_max != 0 || s.latch_max != 0) : (in.endstop_min != 0 || s.latch_min != 0);
}

bool motion_allowed(const State& s, const Input& in, const Config& c, int8_t d) {
  if (endstop_active(s, in, d)) {
    return false;
  }
  const int32_t b = hard_bound(s, c, d);
  return d > 0 ? s.pos < b : s.pos > b;
}

struct Goal {
  int8_t dir = 0;        // 0: come to a stop
  int32_t pr_fine = 0;   // requested speed PR, fine units
  int32_t bound = 0;     // the point motion in `dir` must stop at (target or limit)
  bool pass_ok = false;  // the bound may be overrun above the start speed (set too close)
};

Goal goal_of(const State& s, const Input& in, const Config& c) {
  Goal g;
  g.pr_fine = level_speed(c, s.level) * kSpeedScale;
  switch (s.mode) {
    case Mode::Jog:
      g.dir = motion_allowed(s, in, c, s.jog_dir) ? s.jog_dir : int8_t{0};
      g.bound = hard_bound(s, c, s.jog_dir);
      break;
    case Mode::Position: {
      const int8_t d = s.target > s.pos ? int8_t{1} : (s.target < s.pos ? int8_t{-1} : int8_t{0});
      g.dir = (d != 0 && motion_allowed(s, in, c, d)) ? d : int8_t{0};
      g.bound = s.target;
      g.pass_ok = true;
      break;
    }
    case Mode::Home:
      g.dir = (s.pos > s.target && motion_allowed(s, in, c, -1)) ? int8_t{-1} : int8_t{0};
      g.pr_fine = c.v_slow * kSpeedScale;
      g.bound = s.target;
      // The homing bound only says "give up here"; a Home issued while moving fast may overrun
      // it while braking (the position is unknown anyway, the endstops still guard).
      g.pass_ok = true;
      break;
    case Mode::Idle:
    default:
      break;
  }
  return g;
}

// Distance from the current fine position to `bound` in direction `dir`, fine units.
// |bound - pos| <= 2e9 usteps -> <= 2e15 fine.
int64_t fine_distance(const State& s, int32_t bound) {
  const int64_t d_steps = (static_cast<int64_t>(bound) - s.pos) * s.dir;
  return d_steps * kDist - s.frac;
}

bool can_stop(int32_t v_next, int64_t room_fine, int32_t s_fine, int32_t accel) {
  // At or below the start speed the axis stops at once, so it only has to not pass the bound
  // within this tick, which the arrival clamp ensures. Above it, this tick's travel plus the
  // whole braking travel must end strictly before the bound: reaching it exactly at a higher
  // speed would be an arrival above the start speed.
  return v_next <= s_fine || static_cast<int64_t>(v_next) + stop_distance_fine(v_next, s_fine, accel) < room_fine;
}

void apply_command(State& s, const Input& in, const Config& c, bool& estop, Error& err) {
  const Command& cmd = in.cmd;
  const bool moving_cmd = cmd.kind == CmdKind::Jog || cmd.kind == CmdKind::MoveAbs ||
                          cmd.kind == CmdKind::MoveRel || cmd.kind == CmdKind::Home;
  if (moving_cmd && cmd.level > 1) {
    err = Error::BadCommand;
    return;
  }
  if (moving_cmd && in.blocked != 0) {
    err = Error::Blocked;
    return;
  }
  switch (cmd.kind) {
    case CmdKind::None:
      return;
    case CmdKind::Stop:
      s.mode = Mode::Idle;
      return;
    case CmdKind::EStop:
      s.mode = Mode::Idle;
      estop = true;
      return;
    case CmdKind::Jog:
      if (cmd.dir != 1 && cmd.dir != -1) {
        err = Error::BadCommand;
        return;
      }
      if (endstop_active(s, in, cmd.dir)) {
        err = Error::TowardEndstop;
        return;
      }
      s.mode = Mode::Jog;
      s.jog_dir = cmd.dir;
      s.level = cmd.level;
      return;
    case CmdKind::MoveAbs:
    case CmdKind::MoveRel: {
      if (s.homed == 0) {
        err = Error::NotHomed;
        return;
      }
      // |pos| <= 1e9 and |value| < 2^31 -> the sum fits int64 with room to spare.
      const int64_t t = cmd.kind == CmdKind::MoveAbs ? static_cast<int64_t>(cmd.value)
                                                     : static_cast<int64_t>(s.pos) + cmd.value;
      if (t < c.soft_min || t > c.soft_max) {
        err = Error::OutOfLimits;
        return;
      }
      const int8_t d = t > s.pos ? int8_t{1} : (t < s.pos ? int8_t{-1} : int8_t{0});
      if (d != 0 && endstop_active(s, in, d)) {
        err = Error::TowardEndstop;
        return;
      }
      s.mode = Mode::Position;
      s.target = static_cast<int32_t>(t);
      s.level = cmd.level;
      return;
    }
    case CmdKind::Home:
      if (s.phase == Phase::Stop && endstop_active(s, in, -1)) {
        // Already resting on the min endstop: that is the reference point.
        s.pos = c.home_position;
        s.homed = 1;
        s.mode = Mode::Idle;
        return;
      }
      s.mode = Mode::Home;
      s.homed = 0;
      s.level = 0;
      {
        const int64_t b = static_cast<int64_t>(s.pos) - c.home_travel;
        s.target = b < -kPosMax ? -kPosMax : static_cast<int32_t>(b);
      }
      return;
    default:
      err = Error::BadCommand;
      return;
  }
}

State forced_stop(const State& s) {
  State r = s;
  r.phase = Phase::Stop;
  r.mode = Mode::Idle;
  r.v = 0;
  r.frac = 0;
  r.dir = s.dir < 0 ? int8_t{-1} : int8_t{1};
  return r;
}

}  // namespace

bool config_valid(const Config& c) {
  return c.v_start >= 1 && c.v_start <= c.v_slow && c.v_slow <= c.v_fast && c.v_fast <= kSpeedMax &&
         c.accel >= 1 && c.accel <= kAccelMax && c.soft_min >= -kPosMax && c.soft_min < c.soft_max &&
         c.soft_max <= kPosMax && c.home_travel >= 1 && c.home_travel <= kPosMax &&
         c.home_position >= -kPosMax && c.home_position <= kPosMax;
}

bool state_valid(const State& s) {
  const auto p = static_cast<uint8_t>(s.phase);
  const auto m = static_cast<uint8_t>(s.mode);
  return p <= 3 && m <= 3 && (s.dir == 1 || s.dir == -1) && (s.jog_dir == 1 || s.jog_dir == -1) &&
         s.level <= 1 && s.latch_min <= 1 && s.latch_max <= 1 && s.homed <= 1 && s.pos >= -kPosMax &&
         s.pos <= kPosMax && s.target >= -kPosMax && s.target <= kPosMax && s.v >= 0 &&
         s.v <= kFineSpeedMax && (s.v == 0) == (s.phase == Phase::Stop) && s.frac >= 0 && s.frac < kDistScale;
}

StepResult step(const State& s0, const Input& in, const Config& c) {
  StepResult r{s0, Output{}};
  Output& out = r.out;
  out.dir = s0.dir;
  if (!config_valid(c) || !state_valid(s0)) {
    const bool was_moving = s0.phase != Phase::Stop;
    r.state = forced_stop(s0);
    out.dir = r.state.dir;
    out.cls = Class::EStop;
    out.edge = was_moving && static_cast<uint8_t>(s0.phase) <= 3 ? Edge::X : Edge::I;
    out.error = config_valid(c) ? Error::BadState : Error::BadConfig;
    return r;
  }

  State s = s0;
  // Blocking clears every pending motion (gap G16): the axis brakes and stays stopped.
  if (in.blocked != 0) {
    s.mode = Mode::Idle;
  }
  bool estop = false;
  apply_command(s, in, c, estop, out.error);
  // Link loss (gap G15) ends a jog, which only lives as long as the PC keeps repeating it.
  if (in.link_alive == 0 && s.mode == Mode::Jog) {
    s.mode = Mode::Idle;
  }
  if (in.endstop_min != 0) {
    s.latch_min = 1;
  }
  if (in.endstop_max != 0) {
    s.latch_max = 1;
  }

  const Goal g = goal_of(s, in, c);
  const int32_t s_fine = c.v_start * kSpeedScale;
  const int32_t a = c.accel;
  const bool moving = s.phase != Phase::Stop;

  // ---- classify --------------------------------------------------------------------------
  Class cls = Class::Halt;
  int32_t v_next = 0;
  int64_t steps = 0;
  bool hit_target = false;
  bool hit_bound = false;
  if (estop) {
    cls = Class::EStop;
  } else if (!moving) {
    cls = g.dir != 0 ? Class::Faster : Class::Halt;
  } else if (s.dir < 0 && endstop_active(s, in, -1)) {
    cls = Class::EndMin;
  } else if (s.dir > 0 && endstop_active(s, in, 1)) {
    cls = Class::EndMax;
  } else {
    cls = Class::Same;  // refined below once the new speed and the steps are known
    const int32_t v = s.v;
    // Braking never drops below the start speed; a state slower than that (start speed raised
    // by a config change mid-move) just holds its speed until it stops.
    const int32_t v_brake = v - a > s_fine ? v - a : (v > s_fine ? s_fine : v);
    if (g.dir != s.dir) {
      if (v <= s_fine) {
        cls = Class::Halt;
      } else {
        v_next = v_brake;
      }
    } else {
      const int64_t room = fine_distance(s, g.bound);
      const int32_t pr = g.pr_fine;
      // hi: what PR asks for within one tick's acceleration; lo: full braking.
      const int32_t hi = v < pr ? (v + a < pr ? v + a : pr) : (v - a > pr ? v - a : pr);
      const int32_t lo = v_brake < hi ? v_brake : hi;
      v_next = can_stop(hi, room, s_fine, a) ? hi : best_fit(lo, hi, room, s_fine, a);
    }
    if (cls != Class::Halt) {
      // Steps of this tick, compared against the stop points here where they are emitted (G9).
      const int64_t raw = (static_cast<int64_t>(s.frac) + v_next) / kDist;
      const int64_t d_hard = (static_cast<int64_t>(hard_bound(s, c, s.dir)) - s.pos) * s.dir;
      const int64_t d_goal =
          g.dir == s.dir ? (static_cast<int64_t>(g.bound) - s.pos) * s.dir : std::numeric_limits<int64_t>::max();
      if (g.dir == s.dir && raw >= d_goal && (v_next <= s_fine || !g.pass_ok)) {
        steps = d_goal;
        hit_target = true;
        cls = Class::Halt;
      } else if (raw >= d_hard) {
        steps = d_hard > 0 ? d_hard : 0;
        hit_bound = true;
        cls = Class::Halt;
      } else {
        steps = raw;
        cls = v_next > v ? Class::Faster : (v_next == v ? Class::Same : Class::Slower);
      }
    }
  }

  // ---- transition ------------------------------------------------------------------------
  const Edge e = edge_for(s.phase, cls);
  out.cls = cls;
  out.edge = e;
  switch (e) {
    case Edge::A:
      // Start: DIR is set one tick before the first STEP (setup time), speed jumps to ŠR.
      s.dir = g.dir;
      s.v = s_fine;
      s.frac = 0;
      break;
    case Edge::I:
      if (s.mode == Mode::Position) {
        s.mode = Mode::Idle;  // nothing (more) to do: at the target or refused
      } else if (s.mode == Mode::Home && !estop && endstop_active(s, in, -1)) {
        // Standing in homing on an active min switch (e.g. after the reversal stop of a Home
        // issued while moving up): that is the reference point, as at command time (§6, G19).
        s.pos = c.home_position;
        s.homed = 1;
        s.mode = Mode::Idle;
      } else if (s.mode == Mode::Home && !estop) {
        s.mode = Mode::Idle;
        out.error = Error::HomeFailed;
      }
      break;
    case Edge::G:
    case Edge::H:
      if (e == Edge::G && s.mode == Mode::Home) {
        s.pos = c.home_position;
        s.homed = 1;
      }
      s.mode = Mode::Idle;
      s.v = 0;
      s.frac = 0;
      break;
    case Edge::X:
      s.mode = Mode::Idle;
      s.v = 0;
      s.frac = 0;
      break;
    case Edge::E:
      out.step_speed = steps > 0 ? v_next : 0;
      if (hit_target || hit_bound) {
        if (s.mode == Mode::Position) {
          // Only the target ends a move. A hard stop at the soft limit (a jog too fast to brake
          // before it, retargeted this tick to a target behind the carriage) keeps the move: it
          // starts toward its target from rest next tick instead of being dropped unreported
          // (docs/echo-model.md).
          if (hit_target) s.mode = Mode::Idle;
        } else if (s.mode == Mode::Home) {
          s.mode = Mode::Idle;
          out.error = Error::HomeFailed;
        }
      }
      s.v = 0;
      s.frac = 0;
      break;
    default:
      out.step_speed = v_next;
      s.v = v_next;
      s.frac = static_cast<int32_t>((static_cast<int64_t>(s.frac) + v_next) % kDist);
      break;
  }
  s.phase = edge_target(e, s.phase);
  // steps <= min(d_hard, 1000) and the bound lies within [-kPosMax, kPosMax].
  s.pos = static_cast<int32_t>(s.pos + static_cast<int64_t>(s.dir) * steps);
  out.steps = static_cast<int32_t>(steps);
  out.dir = s.dir;
  // Leaving an endstop: a step away with the switch released ends the refusal.
  if (steps > 0 && s.dir > 0 && in.endstop_min == 0) {
    s.latch_min = 0;
  }
  if (steps > 0 && s.dir < 0 && in.endstop_max == 0) {
    s.latch_max = 0;
  }
  r.state = s;
  return r;
}

}  // namespace ap::xy_axis
