#pragma once
// Exact constant-jerk integration in integers (docs/scurve.md "Integrator").
//
// Over one tick of length dt with constant jerk j the exact solution is (seed-003.md §5.2,
// the [NOT IN THESIS] correction of eqs. 2-25..2-27, applied with the OLD values):
//   p += v dt + a dt^2/2 + j dt^3/6;  v += a dt + j dt^2/2;  a += j dt.
// We count time in ticks (dt = 1) and every kinematic quantity in units of the jerk u used by
// the profile, with the common factors folded in so that every term is an integer:
//   a  = A  * u        (A  in [-2^19, 2^19], |A| <= Tj <= 316227 for plans, docs/scurve.md)
//   v  = V2 * u / 2    (V2 in [0, 2^38]; stored doubled so the j/2 term is integral)
//   p  = P6 * u / 6    (P6 in [0, 6 * 2^41]; stored times six so the j/6 term is integral)
// The jerk of a tick is j * u with j in {-1, 0, +1}. Then one tick is
//   P6 += 3 V2 + 3 A + j;  V2 += 2 A + j;  A += j      (all with the old values)
// which is the exact continuous solution sampled at whole ticks: no rounding anywhere.
#include <cstdint>

namespace ap::xy_scurve {

struct Exact {
  int64_t a = 0;   // A
  int64_t v2 = 0;  // V2 = 2 v / u
  int64_t p6 = 0;  // P6 = 6 p / u
  friend constexpr bool operator==(const Exact&, const Exact&) = default;
};

// One tick with jerk j (in {-1, 0, +1}) from `e`, using the old values.
[[nodiscard]] constexpr Exact advance(const Exact& e, int64_t j) {
  Exact n;
  n.p6 = e.p6 + 3 * e.v2 + 3 * e.a + j;
  n.v2 = e.v2 + 2 * e.a + j;
  n.a = e.a + j;
  return n;
}

// `n` ticks with constant jerk j at once (the same exact solution with dt = n): equal to n
// calls of advance(), used by the planner for the end of a stop without looping.
// Ranges: n <= 2^32 - 1, |a| <= 2^19, results within the ranges above (the caller checks).
[[nodiscard]] constexpr Exact advance_n(const Exact& e, int64_t j, int64_t n) {
  Exact r;
  r.p6 = e.p6 + 3 * e.v2 * n + 3 * e.a * n * n + j * n * n * n;
  r.v2 = e.v2 + 2 * e.a * n + j * n * n;
  r.a = e.a + j * n;
  return r;
}

}  // namespace ap::xy_scurve
