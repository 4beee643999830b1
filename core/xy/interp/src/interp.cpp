// Compiles the header-only interpolators under the core flags and pins the thesis's worked
// examples at compile time (seed-003.md §3.2: (0,0)->(7,3); §2.5 N01: (0,0)->(4000,4000)).
#include "core/xy/interp/arc.hpp"
#include "core/xy/interp/error.hpp"
#include "core/xy/interp/line.hpp"
#include "core/xy/interp/segment.hpp"

namespace ap::xy_interp {
namespace {

constexpr bool thesis_7_3() {
  constexpr int32_t kY[8] = {0, 0, 1, 1, 2, 2, 3, 3};  // seed §3.2, x = 0..7
  Line l{{7, 3, 0}};
  if (l.moves() != 7 || l.position()[1] != kY[0]) return false;
  for (int32_t x = 1; x <= 7; ++x) {
    l.next();
    if (l.position()[0] != x || l.position()[1] != kY[x]) return false;
  }
  return l.done();
}
static_assert(thesis_7_3());

constexpr bool n01_all_diagonal() {
  Line l{{4000, 4000, 0}};
  uint32_t points = 1;
  while (!l.done()) {
    const auto m = l.next();
    if (m[0] != 1 || m[1] != 1 || m[2] != 0) return false;
    ++points;
  }
  return points == 4001;
}
static_assert(n01_all_diagonal());

static_assert(Line::make({Line::kMaxDelta + 1, 0, 0}).error == Error::DeltaOutOfRange);
static_assert(isqrt64(uint64_t{1} << 41) == 1482910U);  // floor(sqrt(2^41)) = 1482910.4

}  // namespace
}  // namespace ap::xy_interp
