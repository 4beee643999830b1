// Properties of every plan in (a fast part of) the documented ranges (docs/scurve.md
// "Properties"), each measured tick by tick from the scaled outputs.
// Generated: moves 1..6000, v_max max(20, moves/10)..20000 moves/s (so a run is at most ~10 s of
// cruise plus the ramps: the binary stays well under 5 s under ASan), j_max 1000..10^8,
// a_max j/1000..10^6 or unlimited (INT32_MAX), j_max <= 10^6 v_max.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <string>

#include "core/xy/scurve/profile.hpp"
#include "run.hpp"

namespace {

using namespace ap::xy_scurve;
using namespace scurve_test;

struct Case {
  uint32_t moves;
  Limits lim;
};

rc::Gen<Case> cases() {
  return rc::gen::mapcat(rc::gen::inRange<uint32_t>(1, 6001), [](uint32_t m) {
    const int32_t vlo = std::max<int32_t>(20, static_cast<int32_t>(m / 10));
    return rc::gen::mapcat(rc::gen::inRange<int32_t>(vlo, 20001), [m](int32_t v) {
      const int32_t jhi = std::min<int32_t>(100000000, v * 1000);  // j <= 10^6 v with margin for speed
      return rc::gen::mapcat(rc::gen::inRange<int32_t>(1000, jhi + 1), [m, v](int32_t j) {
        const int32_t alo = std::max<int32_t>(1, (j + 999) / 1000);
        return rc::gen::map(rc::gen::oneOf(rc::gen::inRange<int32_t>(alo, std::max(alo, 1000000) + 1),
                                           rc::gen::just<int32_t>(2147483647)),
                            [m, v, j](int32_t a) { return Case{m, Limits{v, a, j}}; });
      });
    });
  });
}

std::string check_run(const Case& c) {
  const auto r = plan(c.moves, c.lim);
  SC_CHECK(r.error == Error::None);
  const Plan& p = r.plan;
  SC_CHECK(jerk_unit_within(p, c.lim.j_max));  // the jerk unit u <= J
  auto s = start(p);
  uint32_t prev_moves = 0;
  uint64_t ticks = 0;
  const uint32_t per_tick = static_cast<uint32_t>(c.lim.v_max) / 1000U + 1U;
  while (!finished(p, s)) {
    const auto n = step(p, s);
    ++ticks;
    const int64_t da = n.k.a - s.k.a;
    SC_CHECK(da >= -1);
    SC_CHECK(da <= 1);                                  // |jerk| = |dA| u <= J
    SC_CHECK(accel_within(p, n.k.a, c.lim.a_max));      // |a| <= a_max
    SC_CHECK(n.k.v2 >= 0);                              // v >= 0
    SC_CHECK(velocity_within(p, n.k.v2, c.lim.v_max));  // v <= v_max
    const auto kn = kinematics(p, n);
    const auto ks = kinematics(p, s);
    // The same from the fixed-point trace: |da/dt| <= J (truncation: +1 milli each side).
    SC_CHECK(std::abs(kn.accel_milli - ks.accel_milli) <= static_cast<int64_t>(c.lim.j_max) + 2);
    SC_CHECK(kn.vel_milli <= static_cast<int64_t>(c.lim.v_max) * 1000);
    const uint32_t m = moves_at(p, n);
    SC_CHECK(m >= prev_moves);              // monotone
    SC_CHECK(m - prev_moves <= per_tick);   // <= v_max / 1000 + 1 per tick
    prev_moves = m;
    s = n;
  }
  SC_CHECK(ticks == p.total_ticks);
  SC_CHECK(moves_at(p, s) == c.moves);  // exact arrival
  SC_CHECK(s.k.a == 0);
  SC_CHECK(s.k.v2 == 0);
  SC_CHECK(s.k.p6 == p.p6_end);
  return {};
}

RC_GTEST_PROP(ScurveProperty, LimitsHoldAndArrivalIsExact, ()) {
  const auto c = *cases();
  const auto why = check_run(c);
  RC_ASSERT(why.empty());
}

TEST(ScurveProperty, ThesisLimitsEveryLengthUpTo300) {
  // Exhaustive over short paths with the thesis's limits (moves 1..300: all short-path shapes).
  for (uint32_t m = 1; m <= 300; m += 1) {
    const auto r = plan(m, kThesis);
    ASSERT_EQ(r.error, Error::None) << m;
    const auto t = run(r.plan, start(r.plan));
    const auto& e = t.states.back();
    EXPECT_EQ(moves_at(r.plan, e), m);
    EXPECT_EQ(e.k.v2, 0);
    uint32_t prev = 0;
    for (const auto& s : t.states) {
      const uint32_t mm = moves_at(r.plan, s);
      if (mm < prev) {
        ADD_FAILURE() << "not monotone at " << m;
        break;
      }
      prev = mm;
    }
  }
}

TEST(ScurveProperty, ConstantAccelerationSegmentWhenAmaxBinds) {
  // V J >= A^2 (1000 * 400 >= 200^2): Tj = A / J = 0.5 s and a constant-acceleration segment
  // Ta - 2 Tj = V / A - A / J = 5 - 0.5 = 4.5 s (seed §5.4), within a tick.
  const auto r = plan(20000, {1000, 200, 400});
  ASSERT_EQ(r.error, Error::None);
  EXPECT_EQ(r.plan.len[0], 500U);
  EXPECT_LE(std::abs(static_cast<int64_t>(r.plan.len[1]) - 4500), 1);
  EXPECT_EQ(check_run(Case{20000, {1000, 200, 400}}), "");
}

TEST(ScurveProperty, ShortPathWithConstantAcceleration) {
  // 2 A^3 / J^2 = 2 * 200^3 / 400^2 = 100 moves <= L = 1500 < the full no-cruise distance:
  // the peak is reduced, a_max still reached (seed §5.4's first short-path case).
  const auto r = plan(1500, {1000, 200, 400});
  ASSERT_EQ(r.error, Error::None);
  EXPECT_EQ(r.plan.len[3], 0U);
  EXPECT_GT(r.plan.len[1], 0U);
  EXPECT_EQ(check_run(Case{1500, {1000, 200, 400}}), "");
}

}  // namespace
