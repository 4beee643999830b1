// The thesis's numbers (seed-003.md §5.3.1, §5.4, §12 "Profiles") against the core's plan and
// run at 20 steps/mm: J = 400 moves/s^3, v_max = 1000 moves/s, a_max unlimited.
// Tolerances come from the tick quantisation (docs/scurve.md "Tolerances"): every ramp phase
// Tj is a whole number of 1 ms ticks (rounded down for full ramps, up for short paths), the
// cruise is rounded up, and sigma = moves / planned distance <= 1 scales the rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/xy/scurve/profile.hpp"
#include "run.hpp"

namespace {

using namespace ap::xy_scurve;
using scurve_test::kThesis;

TEST(ScurveThesis, RampToVmaxLasts3162ms) {
  // seed §5.3.1: T_full = 2 sqrt(dv/J) = 3.16228 s; one tick of tolerance.
  const auto r = plan(4000, kThesis);
  ASSERT_EQ(r.error, Error::None);
  const double ramp_ticks = r.plan.len[0] + r.plan.len[1] + r.plan.len[2];
  EXPECT_LE(std::abs(ramp_ticks - 3162.28), 1.0);
  EXPECT_EQ(r.plan.len[1], 0U) << "a_max unlimited: no constant-acceleration segment (seed §5.4)";
  EXPECT_EQ(r.plan.len[4] + r.plan.len[5] + r.plan.len[6], ramp_ticks) << "symmetric deceleration";
}

TEST(ScurveThesis, PeakAccelerationAndRampDistance) {
  const auto r = plan(4000, kThesis);
  ASSERT_EQ(r.error, Error::None);
  auto s = start(r.plan);
  int64_t peak_a = 0;
  const uint32_t ramp = r.plan.len[0] + r.plan.len[1] + r.plan.len[2];
  for (uint32_t t = 0; t < ramp; ++t) {
    s = step(r.plan, s);
    peak_a = std::max(peak_a, kinematics(r.plan, s).accel_milli);
  }
  // 31.6228 mm/s^2 = 632.456 moves/s^2. Tj is rounded down (< 1 tick: < J * 1 ms = 0.4 moves/s^2)
  // and scaled by sigma >= 1 - 1/1000 here: 0.5 moves/s^2.
  EXPECT_NEAR(static_cast<double>(peak_a) / 1000.0, 632.456, 0.5);
  // At the end of the ramp: v = v_max within Tj rounding (2 J Tj * 1 ms = 1.3 moves/s), a = 0.
  const auto k = kinematics(r.plan, s);
  EXPECT_EQ(s.k.a, 0);
  EXPECT_NEAR(static_cast<double>(k.vel_milli) / 1000.0, 1000.0, 1.3);
  EXPECT_LE(k.vel_milli, 1000000);
  // 79.0569 mm = 1581.14 moves; distance ~ Tj^3 so 3 ticks / 1581 relative -> 3 moves, +1 for the floor.
  EXPECT_NEAR(static_cast<double>(moves_at(r.plan, s)), 1581.14, 4.0);
}

TEST(ScurveThesis, ShortSegmentPeaksAt736) {
  // seed §5.4: L = 100 mm = 2000 moves: v_p = (L^2 J / 4)^(1/3) = 36.84 mm/s = 736.8 moves/s,
  // total 4 sqrt(v_p / J) = 5.43 s. Short path: Tj rounded UP (< 1 tick each of the 4 phases).
  const auto r = plan(2000, kThesis);
  ASSERT_EQ(r.error, Error::None);
  EXPECT_EQ(r.plan.len[3], 0U) << "no cruise";
  EXPECT_EQ(r.plan.len[1], 0U) << "no constant acceleration";
  EXPECT_LE(std::abs(static_cast<double>(r.plan.total_ticks) - 5428.8), 4.0);
  const auto t = scurve_test::run(r.plan, start(r.plan));
  int64_t peak_v = 0;
  for (const auto& s : t.states) peak_v = std::max(peak_v, kinematics(r.plan, s).vel_milli);
  // v_p = moves / (2 Tj) per tick: Tj + 1 tick changes it by 736.8 / 1357 = 0.55 moves/s.
  EXPECT_NEAR(static_cast<double>(peak_v) / 1000.0, 736.8, 1.0);
  EXPECT_EQ(moves_at(r.plan, t.states.back()), 2000U);
}

TEST(ScurveThesis, Segment1Lasts7162ms) {
  // seed §5.4: per-axis L = 200 mm = 4000 moves, total 7.162 s. Four ramp phases rounded down and
  // the cruise rounded up: within 3 ticks.
  const auto r = plan(4000, kThesis);
  ASSERT_EQ(r.error, Error::None);
  EXPECT_LE(std::abs(static_cast<double>(r.plan.total_ticks) - 7162.3), 3.0);
  EXPECT_GT(r.plan.len[3], 0U) << "long enough to cruise";
  const auto t = scurve_test::run(r.plan, start(r.plan));
  EXPECT_EQ(t.states.size() - 1, r.plan.total_ticks);
  EXPECT_EQ(moves_at(r.plan, t.states.back()), 4000U);
  EXPECT_EQ(t.states.back().k.a, 0);
  EXPECT_EQ(t.states.back().k.v2, 0);
}

TEST(ScurveThesis, DecelerationStartsAtZeroAcceleration) {
  // seed §9: "Deceleration must always start at zero acceleration". The first tick whose
  // velocity is lower than the previous one starts from A = 0 (for a full and a short path).
  for (uint32_t moves : {4000U, 2000U, 37U}) {
    const auto r = plan(moves, kThesis);
    ASSERT_EQ(r.error, Error::None);
    const auto t = scurve_test::run(r.plan, start(r.plan));
    for (std::size_t i = 1; i < t.states.size(); ++i) {
      if (t.states[i].k.v2 < t.states[i - 1].k.v2) {
        EXPECT_EQ(t.states[i - 1].k.a, 0) << moves << " tick " << i;
        break;
      }
    }
  }
}

TEST(ScurveErrors, BadLimitsChangeNothing) {
  const Limits bad[] = {{0, 1000, 400},          {100001, 1000, 400}, {1000, 0, 400},     {1000, 1000, 0},
                        {1000, 1000, -5},        {-1, 1000, 400},     {1000, 1000, 1000000001},
                        {1000, 1, 1001} /* j > 1000 a: jerk phase under 1 tick */,
                        {1, 2147483647, 1000001} /* j > 10^6 v */};
  for (const auto& l : bad) {
    const auto r = plan(4000, l);
    EXPECT_EQ(r.error, Error::BadLimits) << l.v_max << " " << l.a_max << " " << l.j_max;
    EXPECT_EQ(r.plan.total_ticks, 0U);
    EXPECT_EQ(r.plan.p6_end, 0);
    EXPECT_EQ(r.plan.moves, 0U);
  }
  EXPECT_EQ(plan(4000, {1000, 1, 1000}).error, Error::None) << "j = 1000 a: Tj = 1 tick";
  EXPECT_EQ(plan(4000, {1, 2147483647, 1000000}).error, Error::None) << "j = 10^6 v: Tj = 1 tick";
}

TEST(ScurveErrors, TooLong) {
  // moves <= 2^20; the normalised distance <= 2^41, i.e. moves <= 2^41 J / 10^9 (879609 at J = 400).
  EXPECT_EQ(plan((1U << 20) + 1, {100000, 2147483647, 1000000000}).error, Error::TooLong);
  EXPECT_EQ(plan(1U << 20, {100000, 2147483647, 1000000000}).error, Error::None);
  EXPECT_EQ(plan(800000, kThesis).error, Error::None);
  const auto r = plan(900000, kThesis);
  EXPECT_EQ(r.error, Error::TooLong);
  EXPECT_EQ(r.plan.total_ticks, 0U);
  // A slow jerk: J = 1 moves/s^3 allows only 2199 moves (2^41 / 10^9).
  EXPECT_EQ(plan(2199, {1, 2147483647, 1}).error, Error::None);
  EXPECT_EQ(plan(2200, {1, 2147483647, 1}).error, Error::TooLong);
}

TEST(ScurveErrors, ZeroMovesIsAnEmptyFinishedPlan) {
  const auto r = plan(0, kThesis);
  ASSERT_EQ(r.error, Error::None);
  const auto s = start(r.plan);
  EXPECT_TRUE(finished(r.plan, s));
  EXPECT_EQ(moves_at(r.plan, s), 0U);
  EXPECT_EQ(r.plan.total_ticks, 0U);
  const auto n = step(r.plan, s);
  EXPECT_TRUE(finished(r.plan, n));
  EXPECT_EQ(moves_at(r.plan, n), 0U);
}

TEST(ScurveTrace, MulDivIsExact) {
  // floor(a b / c) with a 128-bit intermediate: cases typed from exact arithmetic.
  EXPECT_EQ(mul_div_floor(0xFFFFFFFFFFFFFFFFULL, 0xFFFFFFFFFFFFFFFFULL, 0xFFFFFFFFFFFFFFFFULL), 0xFFFFFFFFFFFFFFFFULL);
  EXPECT_EQ(mul_div_floor(1ULL << 40, 1ULL << 40, 1ULL << 30), 1ULL << 50);
  EXPECT_EQ(mul_div_floor(10, 10, 3), 33U);
  EXPECT_EQ(mul_div_floor(6000000000000ULL, 1000000ULL, 7ULL), 857142857142857142ULL);
}

}  // namespace
