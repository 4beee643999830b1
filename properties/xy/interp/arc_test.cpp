// Arc (core/xy/interp/arc.hpp) against the thesis (seed-003.md §3.3, §11.5, §12 "Interpolation")
// and docs/interpolation.md "Arc". Expected values are typed in (thesis numbers) or are exact
// integer/geometric predicates evaluated here, never read from the code under test.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "arc_harness.hpp"

namespace {

using namespace ap::interp_test;  // NOLINT(google-build-using-namespace): the harness

int64_t quadrant_moves(int32_t r) {
  const Trace t = trace({0, r}, {r, 0}, Turn::Cw);
  EXPECT_TRUE(t.failure.empty()) << t.failure;
  EXPECT_EQ(t.circle_moves, static_cast<int64_t>(t.points.size()) - 1);  // on-circle end: no tail
  return t.circle_moves;
}

TEST(InterpArc, ThesisQuadrantMoveCounts) {
  // seed §3.3: (0,r) -> (r,0) clockwise: r=5: 7, r=10: 14, r=100: 141, r=2000: 2828 moves.
  EXPECT_EQ(quadrant_moves(5), 7);
  EXPECT_EQ(quadrant_moves(10), 14);
  EXPECT_EQ(quadrant_moves(100), 141);
  EXPECT_EQ(quadrant_moves(2000), 2828);
}

TEST(InterpArc, FirstQuadrantEqualsTheThesisBranches) {
  // The two octant branches the thesis prints (seed §3.3), point by point.
  for (const int32_t r : {1, 2, 3, 5, 10, 37, 100, 2000}) {
    const auto thesis = xy_dda::thesis_quadrant1_cw(r);
    const Trace t = trace({0, r}, {r, 0}, Turn::Cw);
    ASSERT_EQ(thesis.size(), t.points.size()) << r;
    for (std::size_t i = 0; i < thesis.size(); ++i) {
      ASSERT_TRUE(thesis[i][0] == t.points[i][0] && thesis[i][1] == t.points[i][1]) << r << " point " << i;
    }
  }
}

TEST(InterpArc, ThesisN05HalfCircle) {
  // seed §2.5 N05 G02 Y100 I0 J-100 at 20 steps/mm: relative to the centre (300,200) mm, from
  // (0,2000) to (0,-2000) clockwise; passes (2000,0); twice the 2828 moves of a quadrant.
  const Trace t = trace({0, 2000}, {0, -2000}, Turn::Cw);
  ASSERT_TRUE(t.failure.empty()) << t.failure;
  EXPECT_NE(std::find(t.points.begin(), t.points.end(), P{2000, 0}), t.points.end());
  EXPECT_TRUE(std::all_of(t.points.begin(), t.points.end(), [](P p) { return p[0] >= 0; }));
  EXPECT_EQ(t.circle_moves, 2 * 2828);
  EXPECT_EQ(t.points.size(), 2U * 2828U + 1U);
  // The same half circle counter-clockwise goes round the other side, through (-2000, 0).
  const Trace ccw = trace({0, 2000}, {0, -2000}, Turn::Ccw);
  ASSERT_TRUE(ccw.failure.empty()) << ccw.failure;
  EXPECT_NE(std::find(ccw.points.begin(), ccw.points.end(), P{-2000, 0}), ccw.points.end());
  EXPECT_TRUE(std::all_of(ccw.points.begin(), ccw.points.end(), [](P p) { return p[0] <= 0; }));
}

TEST(InterpArc, CrossesQuadrantBoundariesBothWays) {
  // From each quadrant to each other (and the same one, the long way round), r = 500.
  const std::array<P, 4> at{P{400, 300}, P{-300, 400}, P{-400, -300}, P{300, -400}};  // 3-4-5 points
  for (const Turn turn : {Turn::Cw, Turn::Ccw}) {
    for (const P s : at) {
      for (const P e : at) {
        const Trace t = trace(s, e, turn);
        ASSERT_TRUE(t.failure.empty()) << t.failure;
        double total = 0;
        for (std::size_t i = 1; i < t.points.size(); ++i) total += swept(t.points[i - 1], t.points[i], turn);
        const double want = s == e ? 2 * std::numbers::pi : swept(s, e, turn);
        EXPECT_NEAR(total, want, 1e-9);
        // Every axis crossing on the way is visited: the swept angle runs through each multiple
        // of 90 degrees it covers, at a point on that axis.
        int on_axes = 0;
        for (const P p : t.points) on_axes += (p[0] == 0 || p[1] == 0) ? 1 : 0;
        EXPECT_GE(on_axes, static_cast<int>(want / (std::numbers::pi / 2) - 0.5));
      }
    }
  }
}

TEST(InterpArc, OffCircleEndTerminatesAndEndsExactly) {
  // seed §3.3/§11.5: the thesis loops until (x,y) == end. (70,70) is 98.99 from the centre, more
  // than 1/2 off the circle of radius 100, so it is not on the rasterised circle: a full circle
  // from (0,100) never visits it, and the thesis's loop would never stop.
  const Trace full = trace({0, 100}, {0, 100}, Turn::Cw);
  ASSERT_TRUE(full.failure.empty());
  EXPECT_EQ(std::find(full.points.begin(), full.points.end(), P{70, 70}), full.points.end());
  const Trace t = trace({0, 100}, {70, 70}, Turn::Cw);
  ASSERT_TRUE(t.failure.empty()) << t.failure;
  EXPECT_EQ(t.points.back(), (P{70, 70}));
  EXPECT_GT(static_cast<int64_t>(t.points.size()) - 1, t.circle_moves);  // it needed the tail
  EXPECT_LE(static_cast<int64_t>(t.points.size()) - 1, stated_bound({0, 100}, {70, 70}));
  EXPECT_LT(t.points.size(), 100U);  // an eighth of the circle and a short tail
}

// The tail (docs/interpolation.md "Tail bound"): at most ceil(|r_end - r_start|) + 2 moves.
std::string check_tail(P s, P e, Turn turn, const Trace& t) {
  const int64_t tail = static_cast<int64_t>(t.points.size()) - 1 - t.circle_moves;
  const double rs = std::hypot(s[0], s[1]);
  const double re = std::hypot(e[0], e[1]);
  if (static_cast<double>(tail) > std::ceil(std::abs(re - rs) - 1e-12) + 2) return "tail longer than the bound";
  // The circle phase stops at the first point reaching or passing the end's angle.
  const double want = s[0] * e[1] == s[1] * e[0] && int64_t{s[0]} * e[0] + int64_t{s[1]} * e[1] > 0
                          ? 2 * std::numbers::pi : swept(s, e, turn);
  double at = 0;
  for (int64_t i = 1; i <= t.circle_moves; ++i) {
    const double before = at;
    at += swept(t.points[static_cast<std::size_t>(i - 1)], t.points[static_cast<std::size_t>(i)], turn);
    if (i < t.circle_moves && at >= want - 1e-12) return "passed the end's angle before stopping";
    if (i == t.circle_moves && (at < want - 1e-12 || before >= want - 1e-12)) return "stopped at the wrong point";
  }
  return {};
}

// Exhaustive small arcs: every start and end with |coordinates| <= 7, both turns (reaching the
// small radii where a move turns by up to 90 degrees).
TEST(InterpArc, ExhaustiveSmallArcsEndExactlyWithinBounds) {
  constexpr int32_t kB = 7;
  int64_t worst_excess = -100;
  for (int32_t sx = -kB; sx <= kB; ++sx)
    for (int32_t sy = -kB; sy <= kB; ++sy)
      for (int32_t ex = -kB; ex <= kB; ++ex)
        for (int32_t ey = -kB; ey <= kB; ++ey) {
          if ((sx == 0 && sy == 0) || (ex == 0 && ey == 0)) continue;
          for (const Turn turn : {Turn::Cw, Turn::Ccw}) {
            const Trace t = trace({sx, sy}, {ex, ey}, turn);
            ASSERT_TRUE(t.failure.empty()) << t.failure << " (" << sx << "," << sy << ")->(" << ex << "," << ey << ")";
            const std::string why = check_tail({sx, sy}, {ex, ey}, turn, t);
            ASSERT_TRUE(why.empty()) << why << " (" << sx << "," << sy << ")->(" << ex << "," << ey << ")";
            const int64_t tail = static_cast<int64_t>(t.points.size()) - 1 - t.circle_moves;
            const auto dr = static_cast<int64_t>(std::ceil(std::abs(std::hypot(ex, ey) - std::hypot(sx, sy)) - 1e-12));
            worst_excess = std::max(worst_excess, tail - dr);
          }
        }
  std::printf("worst tail - ceil(|dr|) = %lld\n", static_cast<long long>(worst_excess));
}

RC_GTEST_PROP(InterpArc, RandomArcsEndExactlyWithinBounds, ()) {
  const auto coord = rc::gen::inRange<int32_t>(-3000, 3001);
  const P s{*coord, *coord};
  const P e{*coord, *coord};
  RC_PRE(!(s[0] == 0 && s[1] == 0) && !(e[0] == 0 && e[1] == 0));
  const Turn turn = *rc::gen::element(Turn::Cw, Turn::Ccw);
  const Trace t = trace(s, e, turn);
  RC_ASSERT(t.failure.empty());
  RC_ASSERT(check_tail(s, e, turn, t).empty());
}

RC_GTEST_PROP(InterpArc, RandomNearCircleEndsHaveShortTails, ()) {
  // G-code ends are rounded: an end within a few steps of the circle gives a tail of a few steps.
  const auto coord = rc::gen::inRange<int32_t>(-5000, 5001);
  const P s{*coord, *coord};
  RC_PRE(!(s[0] == 0 && s[1] == 0));
  const double angle = *rc::gen::inRange(0, 3600) * std::numbers::pi / 1800;
  const double r = std::hypot(s[0], s[1]) + *rc::gen::inRange(-3, 4);
  const P e{static_cast<int32_t>(std::lround(r * std::cos(angle))), static_cast<int32_t>(std::lround(r * std::sin(angle)))};
  RC_PRE(!(e[0] == 0 && e[1] == 0));
  const Turn turn = *rc::gen::element(Turn::Cw, Turn::Ccw);
  const Trace t = trace(s, e, turn);
  RC_ASSERT(t.failure.empty());
  RC_ASSERT(check_tail(s, e, turn, t).empty());
  RC_ASSERT(static_cast<int64_t>(t.points.size()) - 1 - t.circle_moves <= 7);  // ceil(3 + 1) + 2 + 1
}

TEST(InterpArc, RangeEdgeCircles) {
  // The largest radii: |offsets| = 2^20 (docs/interpolation.md), R2 up to 2^41: a quarter
  // circle at R = 2^20 and short arcs about the corner (R2 = 2^41) in all four quadrants.
  constexpr int32_t kMax = 1 << 20;
  const Trace quarter = trace({kMax, 0}, {0, kMax}, Turn::Ccw);
  EXPECT_TRUE(quarter.failure.empty()) << quarter.failure;
  for (const P c : {P{kMax, kMax}, P{-kMax, kMax}, P{-kMax, -kMax}, P{kMax, -kMax}}) {
    for (const Turn turn : {Turn::Cw, Turn::Ccw}) {
      // An end a little ahead in the turning direction and inside the box: the axis the tangent
      // runs back along gives 2000 steps, the other 1 (a short arc and a tail of ~700 moves).
      const P t = turn == Turn::Ccw ? P{-c[1], c[0]} : P{c[1], -c[0]};
      P e{};
      for (std::size_t i = 0; i < 2; ++i) {
        const int32_t s = c[i] > 0 ? 1 : -1;
        e[i] = c[i] - s * ((t[i] > 0) != (c[i] > 0) ? 2000 : 1);
      }
      const Trace tr = trace(c, e, turn);
      EXPECT_TRUE(tr.failure.empty()) << tr.failure;
      EXPECT_LT(tr.points.size(), 5000U);
    }
  }
}

TEST(InterpArc, BadInputIsRefused) {
  constexpr int32_t kMax = 1 << 20;
  EXPECT_EQ(Arc::make({0, 0}, {5, 0}, Turn::Cw).error, Error::ZeroRadius);
  EXPECT_EQ(Arc::make({5, 0}, {0, 0}, Turn::Cw).error, Error::EndAtCentre);
  EXPECT_EQ(Arc::make({kMax + 1, 0}, {5, 0}, Turn::Cw).error, Error::CoordOutOfRange);
  EXPECT_EQ(Arc::make({5, 0}, {0, -kMax - 1}, Turn::Ccw).error, Error::CoordOutOfRange);
  EXPECT_EQ(Arc::make({INT32_MIN, 0}, {5, 0}, Turn::Ccw).error, Error::CoordOutOfRange);
  auto refused = Arc::make({0, 0}, {5, 0}, Turn::Cw).arc;
  EXPECT_TRUE(refused.done());
  EXPECT_EQ(refused.next(), (std::array<int8_t, 2>{0, 0}));
  EXPECT_EQ(refused.position(), (P{0, 0}));
  EXPECT_EQ(Arc::make({kMax, -kMax}, {-kMax, kMax}, Turn::Cw).error, Error::None);
}

}  // namespace
