#pragma once
// Shared by the scurve tests: a whole run of a plan with the measurements the properties need,
// in exact integer arithmetic on the host (__int128 is fine in tests, not in core/).
#include <cstdint>
#include <string>
#include <vector>

#include "core/xy/scurve/profile.hpp"

namespace scurve_test {

using ap::xy_scurve::Limits;
using ap::xy_scurve::Plan;
using ap::xy_scurve::State;

// The thesis's limits at 20 steps/mm (seed-003.md §5.3.1): J = 20 mm/s^3 = 400 moves/s^3,
// v_max = 50 mm/s = 1000 moves/s, a_max unlimited = the largest allowed value.
inline constexpr Limits kThesis{1000, 2147483647, 400};

__extension__ typedef __int128 i128;  // host-only, exact cross-multiplication

// Physical magnitudes from the core's state (profile.hpp: u = m 6e9 / P6_end moves/s^3 per unit jerk),
// compared exactly as cross-multiplied integers.
inline bool accel_within(const Plan& p, int64_t a_norm, int64_t a_max) {
  const i128 mag = a_norm < 0 ? -i128{a_norm} : i128{a_norm};
  return mag * p.moves * 6000000LL <= i128{a_max} * p.p6_end;  // a = A m 6e6 / P6_end moves/s^2
}
inline bool velocity_within(const Plan& p, int64_t v2, int64_t v_max) {
  return i128{v2} * p.moves * 3000LL <= i128{v_max} * p.p6_end;
}
inline bool jerk_unit_within(const Plan& p, int64_t j_max) {
  return i128{p.moves} * 6000000000000LL / 1000 <= i128{j_max} * p.p6_end;  // u = m * 6e9 / P6_end moves/s^3
}

struct Trace {
  std::vector<State> states;  // from start() to the finished state inclusive
};

inline Trace run(const Plan& p, State s, uint64_t guard = 50000000) {
  Trace t;
  t.states.push_back(s);
  while (!ap::xy_scurve::finished(p, s) && guard-- > 0) {
    s = ap::xy_scurve::step(p, s);
    t.states.push_back(s);
  }
  return t;
}

}  // namespace scurve_test

// In the shared check helpers (used by properties and plain tests): return the failed condition.
#define SC_CHECK(cond) \
  if (!(cond)) return std::string(#cond)
