#pragma once
// The jerk-limited 7-segment S-curve over the path parameter (moves), rest to rest, in whole
// 1 ms ticks, exact in integers (docs/scurve.md; seed-003.md §5.2, §5.4, §9).
//
// Planning (docs/scurve.md "Planning"): the profile is planned in normalised units (jerk u = 1
// per tick^3, see integrator.hpp) with whole-tick segment durations
//   Tj, Tc, Tj, Tv, Tj, Tc, Tj   and jerks +1, 0, -1, 0, -1, 0, +1     (seed §5.4)
// chosen so that at the REQUESTED jerk J the peaks stay within a_max and v_max (ramp
// durations rounded down) and the end distance D reaches `moves` (cruise, or for short paths
// the ramp, rounded up). The normalised profile is then mapped linearly onto [0, moves]:
//   moves_at = floor(moves * P6 / P6_end).
// That is the same profile run with jerk, acceleration and velocity scaled by
// sigma = moves / (D * J / 10^9) <= 1, so every limit still holds and the end is exact.
//
// Ranges (documented in docs/scurve.md; outside them plan() returns an error and an empty plan):
//   moves            0 .. kMaxMoves = 2^20                  (TooLong above)
//   v_max            1 .. kMaxVelocity = 100000 moves/s      (BadLimits outside)
//   a_max            1 .. INT32_MAX moves/s^2 (INT32_MAX = "unlimited")
//   j_max            1 .. kMaxJerk = 10^9 moves/s^3, and j_max <= 1000 a_max, j_max <= 10^6 v_max
//                    (the jerk phase must last at least one tick; BadLimits otherwise)
//   normalised end distance D <= kMaxDistance = 2^41, total ticks <= kMaxTicks = 2^32 - 1 (TooLong)
// Derived bounds: Tj <= 316227 ticks, |A| <= Tj, 0 <= V2 <= 2 * Tj * (Tj + Tc) <= 2 * 10^11,
// 0 <= P6 <= 6 * 2^41, so moves * P6 <= 2^20 * 6 * 2^41 < 2^64 (uint64_t, no __int128 needed).
#include <array>
#include <cstdint>

#include "core/xy/scurve/integrator.hpp"

namespace ap::xy_scurve {

inline constexpr uint32_t kTicksPerSecond = 1000;  // the control tick is 1 ms
inline constexpr uint32_t kMaxMoves = 1U << 20;
inline constexpr int32_t kMaxVelocity = 100000;
inline constexpr int32_t kMaxJerk = 1000000000;
inline constexpr int64_t kMaxDistance = int64_t{1} << 41;
inline constexpr uint64_t kMaxTicks = 0xFFFFFFFFULL;
inline constexpr unsigned kSegments = 7;

struct Limits {
  int32_t v_max;  // moves/s,   1 .. kMaxVelocity
  int32_t a_max;  // moves/s^2, 1 .. INT32_MAX
  int32_t j_max;  // moves/s^3, 1 .. kMaxJerk, <= 1000 a_max, <= 10^6 v_max
};

enum class Error : uint8_t { None, BadLimits, TooLong };

// The normalised jerk of each planned segment (seed-003.md §5.4) and of a stop (request_stop):
// a stop is -1 (ramp a down through 0 to -k1), 0, +1, then a second, small hump -1, 0, +1
// that removes the remainder of the speed (docs/scurve.md "Stop").
inline constexpr std::array<int8_t, kSegments> kPlanJerk{+1, 0, -1, 0, -1, 0, +1};
inline constexpr std::array<int8_t, kSegments> kStopJerk{-1, 0, +1, -1, 0, +1, 0};

struct Plan {
  uint32_t moves = 0;                    // the path length the profile ends at exactly
  std::array<uint32_t, kSegments> len{};  // ticks of each segment: Tj, Tc, Tj, Tv, Tj, Tc, Tj
  int64_t tj = 0;                        // Tj: peak |A| (normalised acceleration)
  int64_t v2_peak = 0;                   // peak V2 = 2 Tj (Tj + Tc)
  int64_t p6_end = 0;                    // P6 at the end = 6 D (0 for an empty plan)
  uint64_t total_ticks = 0;              // 4 Tj + 2 Tc + Tv
};

struct PlanResult {
  Plan plan;
  Error error;
};

// Rest to rest over `moves` (0 -> the empty plan: finished at start, moves_at 0).
[[nodiscard]] PlanResult plan(uint32_t moves, const Limits& lim);

struct State {
  uint8_t seg = 0;                       // current segment 0..6, kSegments when finished
  uint32_t tick = 0;                     // ticks done in the current segment, < its length
  Exact k{};                             // exact A, V2, P6 (integrator.hpp)
  bool stopping = false;                 // running the stop profile (kStopJerk, stop_len)
  std::array<uint32_t, kSegments> stop_len{};  // the stop's segment lengths (zeros unless stopping)
};

[[nodiscard]] State start(const Plan& p);
// One 1 ms tick: the jerk of the current segment applied exactly; a finished state is kept.
[[nodiscard]] State step(const Plan& p, const State& s);
// Moves done: floor(moves * P6 / P6_end); == moves at the planned end.
[[nodiscard]] uint32_t moves_at(const Plan& p, const State& s);
[[nodiscard]] bool finished(const Plan& p, const State& s);
// A controlled, jerk-limited stop from `s` (docs/scurve.md "Stop"): if a > 0, a is ramped
// down with -J and on to the deceleration; the speed is then removed with |a| <= the plan's
// peak. Kept as is when the state is finished, already stopping, already decelerating (a < 0
// or past the cruise) or when the stop would end past the planned end (the plan stops sooner).
[[nodiscard]] State request_stop(const Plan& p, const State& s);

// The normalised jerk (-1, 0, +1) the next tick applies (0 when finished).
[[nodiscard]] int8_t next_jerk(const Plan& p, const State& s);

// Physical values for traces and plots, fixed point in thousandths, truncated toward zero:
//   jerk_milli  = j  * moves * 6e12 / P6_end   (1/1000 moves/s^3, the jerk the next tick applies)
//   accel_milli = A  * moves * 6e9  / P6_end   (1/1000 moves/s^2)
//   vel_milli   = V2 * moves * 3e6  / P6_end   (1/1000 moves/s)
//   pos_milli   = P6 * moves * 1000 / P6_end   (1/1000 moves)
struct Kinematics {
  int64_t jerk_milli = 0;
  int64_t accel_milli = 0;
  int64_t vel_milli = 0;
  int64_t pos_milli = 0;
};
[[nodiscard]] Kinematics kinematics(const Plan& p, const State& s);

// floor(a * b / c) for c > 0 with a 128-bit intermediate built from 64-bit halves (the core
// also builds for the Cortex-M4, which has no __int128). The result must fit 64 bits.
[[nodiscard]] uint64_t mul_div_floor(uint64_t a, uint64_t b, uint64_t c);

}  // namespace ap::xy_scurve
