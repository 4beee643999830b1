// request_stop() (docs/scurve.md "Stop"): from any state, a jerk-limited stop to rest that
// never passes the planned end, with v >= 0 and the limits kept.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <string>

#include "core/xy/scurve/profile.hpp"
#include "run.hpp"

namespace {

using namespace ap::xy_scurve;
using namespace scurve_test;

// Runs `p` for `at` ticks, requests a stop and runs to the end, checking every tick.
std::string check_stop(uint32_t moves, const Limits& lim, uint64_t at) {
  const auto r = plan(moves, lim);
  SC_CHECK(r.error == Error::None);
  const Plan& p = r.plan;
  auto s = start(p);
  for (uint64_t i = 0; i < at && !finished(p, s); ++i) s = step(p, s);
  const State before = s;
  s = request_stop(p, s);
  SC_CHECK(s.k == before.k);  // the request itself moves nothing
  if (before.k.a > 0 && s.stopping) {
    SC_CHECK(next_jerk(p, s) == -1);  // a -> 0 first, with -J
  }
  uint32_t prev = moves_at(p, s);
  uint64_t guard = p.total_ticks + 10;
  while (!finished(p, s) && guard-- > 0) {
    const auto n = step(p, s);
    SC_CHECK(n.k.a - s.k.a >= -1);
    SC_CHECK(n.k.a - s.k.a <= 1);
    SC_CHECK(n.k.a <= p.tj);
    SC_CHECK(n.k.a >= -p.tj);
    SC_CHECK(accel_within(p, n.k.a, lim.a_max));
    SC_CHECK(n.k.v2 >= 0);
    SC_CHECK(velocity_within(p, n.k.v2, lim.v_max));
    SC_CHECK(moves_at(p, n) >= prev);
    prev = moves_at(p, n);
    s = n;
  }
  SC_CHECK(finished(p, s));
  SC_CHECK(s.k.a == 0);
  SC_CHECK(s.k.v2 == 0);
  SC_CHECK(s.k.p6 <= p.p6_end);  // not past the planned end
  SC_CHECK(moves_at(p, s) <= moves);
  return {};
}

RC_GTEST_PROP(ScurveStop, AnywhereEndsAtRestNotPastTheEnd, ()) {
  const auto moves = *rc::gen::inRange<uint32_t>(1, 6001);
  const auto v = *rc::gen::inRange<int32_t>(std::max<int32_t>(20, static_cast<int32_t>(moves / 10)), 20001);
  const auto j = *rc::gen::inRange<int32_t>(1000, std::min<int32_t>(100000000, v * 1000) + 1);
  const auto a = *rc::gen::oneOf(rc::gen::inRange<int32_t>((j + 999) / 1000, std::max((j + 999) / 1000, 1000000) + 1),
                                 rc::gen::just<int32_t>(2147483647));
  const auto r = plan(moves, Limits{v, a, j});
  RC_ASSERT(r.error == Error::None);
  const auto at = *rc::gen::inRange<uint64_t>(0, r.plan.total_ticks + 2);
  const auto why = check_stop(moves, Limits{v, a, j}, at);
  RC_LOG() << why;
  RC_ASSERT(why.empty());
}

TEST(ScurveStop, EveryTickOfTheThesisShortSegment) {
  // Exhaustive over the 2521 stop instants of a short thesis path (200 moves: 4 x 630 ticks).
  const auto r = plan(200, kThesis);
  ASSERT_EQ(r.error, Error::None);
  for (uint64_t at = 0; at <= r.plan.total_ticks; ++at) {
    EXPECT_EQ(check_stop(200, kThesis, at), "") << "stop at tick " << at;
  }
}

TEST(ScurveStop, FromCruiseTakesTheThesisRamp) {
  // Stopping at cruise speed v_max is the mirror of the 0 -> v_max ramp (seed §5.3.1): 3162 ms
  // (one tick per Tj: 2 ticks), 79.0569 mm = 1581.14 moves (as in RampToVmax: 4 moves).
  const auto r = plan(4000, kThesis);
  ASSERT_EQ(r.error, Error::None);
  auto s = start(r.plan);
  const uint32_t cruise_start = r.plan.len[0] + r.plan.len[1] + r.plan.len[2];
  for (uint32_t i = 0; i < cruise_start + 100; ++i) s = step(r.plan, s);
  ASSERT_EQ(s.seg, 3);
  const uint32_t at = moves_at(r.plan, s);
  s = request_stop(r.plan, s);
  ASSERT_TRUE(s.stopping);
  uint32_t ticks = 0;
  while (!finished(r.plan, s)) {
    s = step(r.plan, s);
    ++ticks;
  }
  EXPECT_LE(std::abs(static_cast<double>(ticks) - 3162.28), 2.0);
  EXPECT_NEAR(static_cast<double>(moves_at(r.plan, s) - at), 1581.14, 4.0);
  EXPECT_LT(moves_at(r.plan, s), 4000U);
}

TEST(ScurveStop, DuringDecelerationKeepsThePlan) {
  const auto r = plan(4000, kThesis);
  ASSERT_EQ(r.error, Error::None);
  auto s = start(r.plan);
  for (uint64_t i = 0; i + 100 < r.plan.total_ticks; ++i) s = step(r.plan, s);
  ASSERT_GE(s.seg, 4);
  const auto k = request_stop(r.plan, s);
  EXPECT_FALSE(k.stopping);
  EXPECT_EQ(k.seg, s.seg);
  EXPECT_EQ(k.tick, s.tick);
}

}  // namespace
