// The path executor (core/xy/path) against docs/cnc.md: exact ends, the interpolation bounds at
// every tick, chains through tangent junctions and stops at corners, refusals that change
// nothing, stops and endstops. Expected values come from the geometry and docs/cnc.md.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "core/xy/path/executor.hpp"

namespace {

using ap::xy_path::Error;
using ap::xy_path::Executor;
using ap::xy_path::Kind;
using ap::xy_path::Point;
using ap::xy_path::Segment;

// The thesis's machine (seed-003.md §2.5): 20 steps/mm, v_max 50 mm/s, J 20 mm/s^3, and an
// acceleration above the pure-jerk ramp's peak (31.6 mm/s^2), so the profile is the thesis's.
ap::xy_path::Limits thesis_limits() {
  ap::xy_path::Limits l;
  l.motion = {1000, 2000, 400};
  l.soft_min = {0, 0};
  l.soft_max = {10000, 10000};
  return l;
}

struct Trace {
  std::vector<Point> pos;             // after every tick
  std::vector<ap::xy_path::TickOut> out;
  std::vector<std::int64_t> vel;      // path speed, 1/1000 moves/s, after every tick
  ap::xy_path::Halt halt = ap::xy_path::Halt::None;
};

Trace run(Executor& e, Point p, std::size_t max_ticks = 200000, ap::xy_path::TickIn in = {}) {
  Trace r;
  for (std::size_t t = 0; t < max_ticks && e.active(); ++t) {
    ap::xy_path::Halt h = ap::xy_path::Halt::None;
    r.out.push_back(e.tick(in, p, h));
    r.pos.push_back(p);
    r.vel.push_back(e.kinematics().vel_milli);
    if (h != ap::xy_path::Halt::None) {
      r.halt = h;
      break;
    }
  }
  return r;
}

Segment line(Point a, Point b) { return {Kind::Line, a, b, {}}; }

TEST(PathExecutor, TheThesisFirstSegmentEndsExactlyAtBothAxesTogether) {
  Executor e;
  ASSERT_EQ(e.add(line({0, 0}, {4000, 4000}), thesis_limits()), Error::None);
  e.close();
  const Trace r = run(e, {0, 0});
  ASSERT_FALSE(e.active());
  EXPECT_EQ(r.pos.back(), (Point{4000, 4000}));
  // A 45 degree line: the axes move together on every tick (Bresenham: all moves diagonal).
  for (const Point& p : r.pos) EXPECT_EQ(p[0], p[1]);
  // Per-axis L = 200 mm at v_max 50 mm/s, J 20 mm/s^3: 7.162 s (seed-003.md §5.4), within a
  // few ticks of the whole-tick plan and the counting tick.
  EXPECT_NEAR(static_cast<double>(r.pos.size()), 7162.0, 10.0);
}

TEST(PathExecutor, EveryTickLiesWithinHalfAStepOfTheIdealLine) {
  Executor e;
  const Point a{100, 200};
  const Point b{7100, 3200};
  ASSERT_EQ(e.add(line(a, b), thesis_limits()), Error::None);
  e.close();
  const Trace r = run(e, a);
  EXPECT_EQ(r.pos.back(), b);
  for (const Point& p : r.pos) {
    // Major axis x: the ideal y at this x; the rasterised y is within 1/2 step.
    const double y = a[1] + (static_cast<double>(p[0] - a[0]) * (b[1] - a[1])) / (b[0] - a[0]);
    EXPECT_LE(std::abs(p[1] - y), 0.5 + 1e-9);
  }
}

TEST(PathExecutor, TheThesisHalfCircleStaysOnItsCircleAndEndsExactly) {
  // N05 G02 Y100 I0 J-100 at 20 steps/mm: from (6000,6000) around (6000,4000) to (6000,2000), CW.
  Executor e;
  ap::xy_path::Limits l = thesis_limits();
  ASSERT_EQ(e.add({Kind::ArcCw, {6000, 6000}, {6000, 2000}, {6000, 4000}}, l), Error::None);
  e.close();
  const Trace r = run(e, {6000, 6000});
  EXPECT_EQ(r.pos.back(), (Point{6000, 2000}));
  bool passed_right = false;
  for (const Point& p : r.pos) {
    const double rad = std::hypot(p[0] - 6000.0, p[1] - 4000.0);
    EXPECT_LT(std::abs(rad - 2000.0), 0.5);
    EXPECT_GE(p[0], 6000);  // clockwise from the top: the right half only
    passed_right = passed_right || p == Point{8000, 4000};
  }
  EXPECT_TRUE(passed_right);
}

TEST(PathExecutor, TangentLineArcLineIsOneChainThatKeepsItsSpeed) {
  // N04, N05, N06 of the thesis's program: line +X, CW half circle, line -X (seed-003.md §2.5).
  Executor e;
  const auto l = thesis_limits();
  ASSERT_EQ(e.add(line({4000, 6000}, {6000, 6000}), l), Error::None);
  ASSERT_EQ(e.add({Kind::ArcCw, {6000, 6000}, {6000, 2000}, {6000, 4000}}, l), Error::None);
  ASSERT_EQ(e.add(line({6000, 2000}, {2000, 2000}), l), Error::None);
  e.close();
  const Trace r = run(e, {4000, 6000});
  EXPECT_EQ(r.pos.back(), (Point{2000, 2000}));
  // At the junctions the path is moving: the speed is above zero where the arc starts.
  for (std::size_t t = 0; t < r.pos.size(); ++t) {
    if (r.pos[t] == Point{6000, 6000}) {
      EXPECT_GT(r.vel[t], 0);
    }
  }
  // One chain: no standstill in the middle (the S-curve creeps only at its two ends, where its
  // speed is below 1/1000 move/s for a few ticks).
  std::size_t still = 0;
  for (std::size_t t = 0; t < r.pos.size(); ++t) {
    if (r.vel[t] == 0 && r.pos[t][0] > 4010 && r.pos[t][0] < 7990) ++still;
  }
  EXPECT_EQ(still, 0U);
  bool at_arc_end = false;
  for (std::size_t t = 0; t < r.pos.size(); ++t) {
    if (r.pos[t] == Point{6000, 2000}) {
      at_arc_end = true;
      EXPECT_GT(r.vel[t], 0);
    }
  }
  EXPECT_TRUE(at_arc_end);
}

TEST(PathExecutor, ACornerEndsTheChainAtRest) {
  // N01 then N03: (0,0)->(4000,4000)->(4000,6000), a 45 degree turn: a stop at the corner.
  Executor e;
  const auto l = thesis_limits();
  ASSERT_EQ(e.add(line({0, 0}, {4000, 4000}), l), Error::None);
  ASSERT_EQ(e.add(line({4000, 4000}, {4000, 6000}), l), Error::None);
  e.close();
  const Trace r = run(e, {0, 0});
  EXPECT_EQ(r.pos.back(), (Point{4000, 6000}));
  bool stood_at_corner = false;
  for (std::size_t t = 0; t < r.pos.size(); ++t) {
    if (r.pos[t] == Point{4000, 4000} && r.vel[t] == 0) stood_at_corner = true;
  }
  EXPECT_TRUE(stood_at_corner);
}

TEST(PathExecutor, AnOpenChainWaitsForItsEnd) {
  Executor e;
  ASSERT_EQ(e.add(line({0, 0}, {1000, 0}), thesis_limits()), Error::None);
  Point p{0, 0};
  ap::xy_path::Halt h;
  for (int t = 0; t < 50; ++t) (void)e.tick({}, p, h);
  EXPECT_EQ(p, (Point{0, 0}));  // a tangent continuation may still come
  EXPECT_EQ(e.status(), ap::xy_path::Status::Waiting);
  e.close();
  (void)run(e, p);
}

TEST(PathExecutor, RefusalsNameTheCauseAndChangeNothing) {
  const auto l = thesis_limits();
  Executor e;
  EXPECT_EQ(e.add(line({0, 0}, {0, 0}), l), Error::ZeroLength);
  EXPECT_EQ(e.add(line({0, 0}, {10001, 0}), l), Error::OutOfLimits);
  EXPECT_EQ(e.add(line({0, 0}, {-1, 5}), l), Error::OutOfLimits);
  // A carriage standing outside the limits (an encoder start below the minimum) may move back in.
  EXPECT_EQ(e.add(line({0, -5}, {10, 10}), l), Error::None);
  e.clear();
  EXPECT_EQ(e.add({Kind::ArcCw, {100, 100}, {300, 100}, {100, 100}}, l), Error::ArcZeroRadius);
  // End radius 2000 vs start radius 1990: more than max(2 steps, 0.1 %).
  EXPECT_EQ(e.add({Kind::ArcCw, {5000, 6000}, {5000, 2010}, {5000, 4000}}, l), Error::ArcRadiusMismatch);
  // Within the tolerance: 2 steps.
  EXPECT_EQ(e.add({Kind::ArcCw, {5000, 6000}, {5000, 2002}, {5000, 4000}}, l), Error::None);
  e.clear();
  // A CW arc from the top around (5000, 4000) passes x = 7000: inside; the same circle's left
  // extreme (3000) is not swept, so a soft minimum at 3500 does not matter.
  ap::xy_path::Limits tight = l;
  tight.soft_min = {3500, 0};
  EXPECT_EQ(e.add({Kind::ArcCw, {5000, 6000}, {5000, 2000}, {5000, 4000}}, tight), Error::None);
  e.clear();
  // Counter-clockwise it sweeps the left half: x = 3000 < 3500.
  EXPECT_EQ(e.add({Kind::ArcCcw, {5000, 6000}, {5000, 2000}, {5000, 4000}}, tight), Error::OutOfLimits);
  EXPECT_FALSE(e.active());
  for (std::size_t k = 0; k < ap::xy_path::kQueue; ++k) {
    ASSERT_EQ(e.add(line({static_cast<std::int32_t>(k * 10), 0}, {static_cast<std::int32_t>(k * 10 + 10), (k % 2 == 0) ? 5 : 0}), l),
              Error::None);
  }
  EXPECT_EQ(e.queued(), ap::xy_path::kQueue);
  EXPECT_EQ(e.add(line({160, 0}, {170, 0}), l), Error::QueueFull);
  EXPECT_EQ(e.queued(), ap::xy_path::kQueue);
  ap::xy_path::Limits bad = l;
  bad.motion.j_max = 2000 * 1000 + 1;  // more than 1000 a_max: scurve's range
  e.clear();
  EXPECT_EQ(e.add(line({0, 0}, {10, 0}), bad), Error::BadLimits);
  EXPECT_FALSE(e.active());
}

TEST(PathExecutor, AStopEndsAtRestBeforeTheEndAndNeverSpeedsUp) {
  Executor e;
  ASSERT_EQ(e.add(line({0, 0}, {9000, 3000}), thesis_limits()), Error::None);
  e.close();
  Point p{0, 0};
  ap::xy_path::Halt h;
  for (int t = 0; t < 2500; ++t) (void)e.tick({}, p, h);
  ASSERT_GT(e.kinematics().accel_milli, 0);  // still accelerating: the stop ramps a to 0 first
  e.stop();
  EXPECT_EQ(e.add(line({9000, 3000}, {9000, 0}), thesis_limits()), Error::Stopping);
  std::int64_t prev_v = e.kinematics().vel_milli;
  std::int64_t prev_a = e.kinematics().accel_milli;
  bool decelerated = false;
  while (e.active()) {
    (void)e.tick({}, p, h);
    const auto k = e.kinematics();
    // Jerk-limited (seed-003.md §9): the acceleration falls to 0 before the speed falls; from
    // a <= 0 on, the speed never rises.
    if (prev_a > 0) {
      EXPECT_LE(k.accel_milli, prev_a);
    } else {
      EXPECT_LE(k.vel_milli, prev_v);
      decelerated = true;
    }
    prev_v = k.vel_milli;
    prev_a = k.accel_milli;
  }
  EXPECT_TRUE(decelerated);
  EXPECT_LT(p[0], 9000);
  EXPECT_EQ(e.queued(), 0U);
}

TEST(PathExecutor, AnEndstopHaltsBeforeTheStepTowardIt) {
  Executor e;
  ASSERT_EQ(e.add(line({5000, 5000}, {1000, 5000}), thesis_limits()), Error::None);
  e.close();
  ap::xy_path::TickIn in;
  Point p{5000, 5000};
  ap::xy_path::Halt h = ap::xy_path::Halt::None;
  for (int t = 0; t < 1500; ++t) (void)e.tick(in, p, h);
  const Point at = p;
  in.toward_min_blocked[0] = true;
  const auto o = e.tick(in, p, h);
  EXPECT_EQ(h, ap::xy_path::Halt::Endstop);
  EXPECT_EQ(o.steps[0], 0);
  EXPECT_EQ(p, at);
  EXPECT_FALSE(e.active());
}

// Random lines inside the limits: exact end, the cross-axis bound at every tick, no more steps
// per tick than v_max allows (docs/cnc.md "Safety properties").
RC_GTEST_PROP(PathExecutorProps, RandomLinesEndExactlyWithinTheirBounds, ()) {
  const auto l = thesis_limits();
  const Point a{*rc::gen::inRange(0, 10001), *rc::gen::inRange(0, 10001)};
  const Point b{*rc::gen::inRange(0, 10001), *rc::gen::inRange(0, 10001)};
  RC_PRE(a != b);
  Executor e;
  RC_ASSERT(e.add(line(a, b), l) == Error::None);
  e.close();
  const Trace r = run(e, a);
  RC_ASSERT(r.pos.back() == b);
  const bool x_major = std::abs(b[0] - a[0]) >= std::abs(b[1] - a[1]);
  for (std::size_t t = 0; t < r.pos.size(); ++t) {
    const Point& p = r.pos[t];
    const std::size_t M = x_major ? 0 : 1;
    const std::size_t m = 1 - M;
    const double ideal = a[m] + (static_cast<double>(p[M] - a[M]) * (b[m] - a[m])) / (b[M] - a[M]);
    RC_ASSERT(std::abs(p[m] - ideal) <= 0.5 + 1e-9);
    RC_ASSERT(r.out[t].steps[0] <= 2 * (1000 / 1000 + 1));
    RC_ASSERT(r.out[t].steps[1] <= 2 * (1000 / 1000 + 1));
  }
}

// Random arcs: exact end, radial error < 1/2 step on the circle, the move count bound the queue
// uses for chain lengths holds (docs/cnc.md "Chains").
RC_GTEST_PROP(PathExecutorProps, RandomArcsEndExactlyOnTheirCircle, ()) {
  auto l = thesis_limits();
  l.soft_min = {-100000, -100000};
  l.soft_max = {100000, 100000};
  const Point c{*rc::gen::inRange(-1000, 1000), *rc::gen::inRange(-1000, 1000)};
  const double r = *rc::gen::inRange(3, 1500);
  const double th0 = *rc::gen::inRange(0, 360) * M_PI / 180.0;
  const double th1 = *rc::gen::inRange(0, 360) * M_PI / 180.0;
  const Point s{c[0] + static_cast<std::int32_t>(std::lround(r * std::cos(th0))), c[1] + static_cast<std::int32_t>(std::lround(r * std::sin(th0)))};
  Point en{c[0] + static_cast<std::int32_t>(std::lround(r * std::cos(th1))), c[1] + static_cast<std::int32_t>(std::lround(r * std::sin(th1)))};
  const bool cw = *rc::gen::arbitrary<bool>();
  Executor e;
  const Error err = e.add({cw ? Kind::ArcCw : Kind::ArcCcw, s, en, c}, l);
  RC_PRE(err == Error::None);
  e.close();
  const Trace run_ = run(e, s);
  RC_ASSERT(run_.pos.back() == en);
  const double rs = std::hypot(s[0] - c[0], s[1] - c[1]);
  const double re = std::hypot(en[0] - c[0], en[1] - c[1]);
  for (const Point& p : run_.pos) {
    const double rad = std::hypot(p[0] - c[0], p[1] - c[1]);
    // On the circle through the start, or on the straight tail to an end off it (within the
    // two radii).
    RC_ASSERT(rad < std::max(rs, re) + 0.5 + 1e-9);
    RC_ASSERT(rad > std::min(rs, re) - 0.5 - 1e-9 - 1.0);
  }
}

}  // namespace
