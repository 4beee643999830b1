// Test-side driver and per-tick checker for the axis core. The checker restates the
// requirements of docs/motion.md from the outside (continuous stopping distance, own endstop and
// block bookkeeping); it never calls the core's own planning helpers.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include "core/xy/axis/axis.hpp"

namespace ap::xy_axis::test {

inline constexpr int64_t kFine = kDistScale;

// Runs one move from rest to rest and reports what happened.
struct MoveResult {
  int64_t ticks = 0;           // ticks from the command to the tick that stopped at the target
  int32_t final_pos = 0;
  int32_t max_fine_speed = 0;
  int32_t arrival_fine_speed = 0;
  int64_t overshoot = 0;       // steps beyond the target in the direction of the move
  bool arrived = false;
};

inline MoveResult run_move(State s, const Config& c, int32_t target, uint8_t level, int64_t max_ticks) {
  MoveResult r;
  Input in;
  in.cmd = Command{CmdKind::MoveAbs, 0, level, target};
  const int32_t start = s.pos;
  const int64_t dir = target >= start ? 1 : -1;
  for (int64_t t = 1; t <= max_ticks; ++t) {
    const StepResult sr = step(s, in, c);
    in.cmd = Command{};
    s = sr.state;
    r.max_fine_speed = std::max(r.max_fine_speed, sr.out.step_speed);
    r.overshoot = std::max<int64_t>(r.overshoot, (static_cast<int64_t>(s.pos) - target) * dir);
    if (s.phase == Phase::Stop && s.mode == Mode::Idle) {
      r.ticks = t;
      r.final_pos = s.pos;
      r.arrival_fine_speed = sr.out.step_speed;
      r.arrived = s.pos == target;
      return r;
    }
  }
  r.final_pos = s.pos;
  return r;
}

// Continuous braking distance from fine speed v to the start speed, in usteps, rounded up:
// the discrete core must never need more (it brakes along a sum of right-endpoint speeds).
inline int64_t continuous_brake_usteps(int32_t v_fine, const Config& c) {
  const long double v = static_cast<long double>(v_fine) / kSpeedScale;
  const long double s = c.v_start;
  if (v <= s) return 0;
  return static_cast<int64_t>(std::ceil((v * v - s * s) / (2.0L * c.accel)));
}

}  // namespace ap::xy_axis::test
