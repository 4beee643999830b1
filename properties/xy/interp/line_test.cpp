// Line (core/xy/interp/line.hpp) against the thesis (seed-003.md §3.2, §12 "Interpolation") and
// the documented tie rule (docs/interpolation.md "Line"): expected values are typed in or
// follow from the rule, never read from the code under test.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "core/xy/interp/line.hpp"

namespace {

using ap::xy_interp::Error;
using ap::xy_interp::Line;
using Delta = std::array<int32_t, 3>;

std::vector<Delta> points_of(Delta d) {
  Line l{d};
  std::vector<Delta> pts{l.position()};
  while (!l.done()) {
    l.next();
    pts.push_back(l.position());
  }
  return pts;
}

// Every requirement of seed §3.2/§12 on one line; the rule: after k major moves, axis i is at
// sign(d_i) * floor((2*k*|d_i| + n) / (2n)) (nearest, half away from the start).
// Returns a failure message or an empty string.
std::string check_line(Delta d) {
  Line l{d};
  int64_t n = 0;
  for (const int32_t v : d) n = std::max<int64_t>(n, std::llabs(v));
  if (l.moves() != static_cast<uint64_t>(n)) return "moves() != max|d_i|";
  std::size_t major = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    if (std::llabs(d[i]) == n) { major = i; break; }
  }
  Delta prev = l.position();
  if (prev != Delta{0, 0, 0}) return "does not start at the origin";
  int64_t points = 1;
  for (int64_t k = 1; k <= n; ++k) {
    if (l.done()) return "done() before moves()";
    const auto m = l.next();
    const Delta p = l.position();
    ++points;
    for (std::size_t i = 0; i < 3; ++i) {
      if (m[i] < -1 || m[i] > 1) return "move component outside {-1,0,1}";
      if (p[i] - prev[i] != m[i]) return "move does not match position";
      const int64_t a = std::llabs(d[i]);
      const int64_t y = std::llabs(p[i]);
      if (p[i] != 0 && ((p[i] > 0) != (d[i] > 0))) return "moved against the delta's sign";
      // |ideal - actual| <= 1/2 step, exactly in integers: |2*(k*a - n*y)| <= n.
      if (std::llabs(2 * (k * a - n * y)) > n) return "cross-axis error above 1/2 step";
      if (y != (2 * k * a + n) / (2 * n)) return "not the documented rounding (half away from start)";
    }
    if (m[major] == 0) return "major axis did not move";
    prev = p;
  }
  if (!l.done()) return "not done after moves()";
  if (l.position() != d) return "end point missed";
  if (points != n + 1) return "point count != moves()+1";
  if (l.next() != std::array<int8_t, 3>{0, 0, 0} || l.position() != d) return "next() after done moved";
  return {};
}

TEST(InterpLine, ThesisSevenByThree) {
  // seed §3.2: (0,0)->(7,3) gives (0,0),(1,0),(2,1),(3,1),(4,2),(5,2),(6,3),(7,3).
  const std::vector<Delta> want{{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0}, {4, 2, 0}, {5, 2, 0}, {6, 3, 0}, {7, 3, 0}};
  EXPECT_EQ(points_of({7, 3, 0}), want);
}

TEST(InterpLine, ThesisN01Is4001DiagonalPoints) {
  // seed §2.5/§12: (0,0)->(4000,4000): 4001 points, every move diagonal.
  Line l{{4000, 4000, 0}};
  EXPECT_EQ(l.moves(), 4000U);
  int points = 1;
  while (!l.done()) {
    const auto m = l.next();
    ASSERT_EQ(m, (std::array<int8_t, 3>{1, 1, 0}));
    ++points;
  }
  EXPECT_EQ(points, 4001);
  EXPECT_EQ(l.position(), (Delta{4000, 4000, 0}));
}

TEST(InterpLine, TiesRoundHalfAwayFromTheStart) {
  // The thesis's all-octant loop (seed §3.2, run by hand): (4,1) passes (2,1); (2,1) passes
  // (1,1); (4,3) passes (2,2); (1,4) passes (1,2); mirrored in every sign.
  EXPECT_EQ(points_of({4, 1, 0}), (std::vector<Delta>{{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0}, {4, 1, 0}}));
  EXPECT_EQ(points_of({2, 1, 0}), (std::vector<Delta>{{0, 0, 0}, {1, 1, 0}, {2, 1, 0}}));
  EXPECT_EQ(points_of({4, 3, 0})[2], (Delta{2, 2, 0}));
  EXPECT_EQ(points_of({1, 4, 0}), (std::vector<Delta>{{0, 0, 0}, {0, 1, 0}, {1, 2, 0}, {1, 3, 0}, {1, 4, 0}}));
  EXPECT_EQ(points_of({-4, -1, 0})[2], (Delta{-2, -1, 0}));
  EXPECT_EQ(points_of({4, -1, 0})[2], (Delta{2, -1, 0}));
  EXPECT_EQ(points_of({0, 4, -1})[2], (Delta{0, 2, -1}));
}

TEST(InterpLine, ZeroDeltaIsOnePoint) {
  Line l{{0, 0, 0}};
  EXPECT_EQ(l.moves(), 0U);
  EXPECT_TRUE(l.done());
  EXPECT_EQ(l.next(), (std::array<int8_t, 3>{0, 0, 0}));
  EXPECT_EQ(l.position(), (Delta{0, 0, 0}));
}

TEST(InterpLine, OutOfRangeIsRefusedAndBuildsNothing) {
  constexpr int32_t kMax = 1 << 24;  // docs/interpolation.md: |delta_i| <= 2^24
  EXPECT_TRUE(Line::valid({kMax, -kMax, 0}));
  for (const Delta d : {Delta{kMax + 1, 0, 0}, Delta{0, -kMax - 1, 0}, Delta{0, 0, std::numeric_limits<int32_t>::min()},
                        Delta{std::numeric_limits<int32_t>::max(), 1, 1}}) {
    EXPECT_FALSE(Line::valid(d));
    const auto r = Line::make(d);
    EXPECT_EQ(r.error, Error::DeltaOutOfRange);
    EXPECT_EQ(r.line.moves(), 0U);
    EXPECT_TRUE(r.line.done());
    Line direct{d};  // the constructor's documented refusal: a zero-length line
    EXPECT_EQ(direct.moves(), 0U);
    EXPECT_EQ(direct.next(), (std::array<int8_t, 3>{0, 0, 0}));
  }
  const auto ok = Line::make({3, -2, 1});
  EXPECT_EQ(ok.error, Error::None);
  EXPECT_EQ(ok.line.moves(), 3U);
}

// Exhaustive: every 2-D delta with |dx|, |dy| <= 128 (66 049 lines, 5.7e6 moves), each in the
// XY, XZ and YZ placements of the first one.
TEST(InterpLine, Exhaustive2DUpTo128) {
  constexpr int32_t kB = 128;
  for (int32_t dx = -kB; dx <= kB; ++dx) {
    for (int32_t dy = -kB; dy <= kB; ++dy) {
      const std::string why = check_line({dx, dy, 0});
      ASSERT_TRUE(why.empty()) << why << " for (" << dx << ", " << dy << ")";
    }
  }
  for (int32_t a = -16; a <= 16; ++a) {
    for (int32_t b = -16; b <= 16; ++b) {
      ASSERT_TRUE(check_line({a, 0, b}).empty()) << a << " " << b;
      ASSERT_TRUE(check_line({0, a, b}).empty()) << a << " " << b;
    }
  }
}

RC_GTEST_PROP(InterpLine, Random2DLinesMeetTheRequirements, ()) {
  const auto dx = *rc::gen::inRange<int32_t>(-30000, 30001);
  const auto dy = *rc::gen::inRange<int32_t>(-30000, 30001);
  const std::string why = check_line({dx, dy, 0});
  RC_ASSERT(why.empty());
}

RC_GTEST_PROP(InterpLine, Random3DLinesMeetTheRequirements, ()) {
  const auto dx = *rc::gen::inRange<int32_t>(-10000, 10001);
  const auto dy = *rc::gen::inRange<int32_t>(-10000, 10001);
  const auto dz = *rc::gen::inRange<int32_t>(-10000, 10001);
  const std::string why = check_line({dx, dy, dz});
  RC_ASSERT(why.empty());
}

// The range's edge: a full line of 2^24 moves in 3 axes; the per-point error bound at this range
// is the proof's (interp.bresenham.*), here: every move's size, the per-axis totals, the end.
TEST(InterpLine, FullRangeLineIsExact) {
  constexpr int32_t kMax = 1 << 24;
  const std::array<int32_t, 3> d{-kMax, kMax - 1, kMax / 3};
  Line l{d};
  ASSERT_EQ(l.moves(), static_cast<uint32_t>(kMax));
  std::array<int64_t, 3> sum{0, 0, 0};
  uint32_t calls = 0;
  bool sizes = true;  // X (major) -1 every call; Y, Z 0 or +1
  while (!l.done()) {
    const auto m = l.next();
    sizes = sizes && m[0] == -1 && (m[1] == 0 || m[1] == 1) && (m[2] == 0 || m[2] == 1);
    sum[0] += m[0];
    sum[1] += m[1];
    sum[2] += m[2];
    ++calls;
  }
  EXPECT_TRUE(sizes);
  EXPECT_EQ(calls, static_cast<uint32_t>(kMax));
  EXPECT_EQ(sum, (std::array<int64_t, 3>{-kMax, kMax - 1, kMax / 3}));
  EXPECT_EQ(l.position(), d);
}

}  // namespace
