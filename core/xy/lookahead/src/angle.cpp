// Compiles angle.hpp under the core flags and pins a few first-quadrant values at compile time
// (angle.hpp "Exact by construction"; docs/lookahead.md "Angle"). The other quadrants are
// checked by the LookaheadAngle tests, so a quadrant bug (thesis defect (a), seed-003.md §6)
// shows up there as a failing test, not as a build error.
#include "core/xy/lookahead/angle.hpp"

#include <cstdint>

namespace ap::xy_lookahead {
namespace {
constexpr bool is(int64_t y, int64_t x, int32_t mdeg) {
  const Angle a = atan2_mdeg(y, x);
  return a.ok() && a.mdeg == mdeg;
}
static_assert(is(0, 1, 0));
static_assert(is(1, 0, 90'000));
static_assert(is(1, 1, 45'000));
static_assert(is(INT64_MAX, INT64_MAX, 45'000));
static_assert(!atan2_mdeg(0, 0).ok());
}  // namespace
}  // namespace ap::xy_lookahead
