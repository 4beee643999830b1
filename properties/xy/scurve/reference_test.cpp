// The core's whole-tick integer profile against the continuous 7-segment reference
// (models/xy/scurve continuous.hpp, seed-003.md §5.4) at every tick (docs/scurve.md "Tolerances").
// The core's durations differ from the continuous ones by under one tick per ramp phase
// (4 phases), its peak acceleration Tj u is lower by under one tick of jerk (relative 1/Tj) and
// its peak speed Tj (Tj + Tc) u by under 2/Tj relative (Tj rounded down, squared), which
// stretches the whole profile of length T by up to 2 T / Tj; its velocity is scaled by
// sigma <= 1 with 1 - sigma <= v_peak * 1 ms / L (the cruise rounded up by under one tick) or
// <= 3 / Tj (a short path: Tj rounded up, distance ~ Tj^3).
// So at the same instant, with shift = 4 ms + 2 T / Tj (Tj in ticks):
//   |dv| <= a_peak * shift + v_peak (v_peak * 1 ms / L + 3 / Tj) + 1 moves/s,
//   |dp| <= v_peak * shift + 2 moves (the floor of moves_at and sigma).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/xy/scurve/profile.hpp"
#include "models/xy/scurve/continuous.hpp"

namespace {

using namespace ap::xy_scurve;
namespace m = ap::model::xy_scurve;

struct Worst {
  double dv = 0, dp = 0, tv = 0, tp = 0;
};

Worst compare(uint32_t moves, const Limits& lim) {
  const auto r = plan(moves, lim);
  EXPECT_EQ(r.error, Error::None);
  const auto ref = m::continuous_plan(moves, lim.v_max, lim.a_max, lim.j_max);
  const double shift = 0.004 + 2.0 * ref.total / std::floor(ref.dur[0] * 1000.0);
  const double tol_v = ref.a_peak * shift + ref.v_peak * (ref.v_peak * 0.001 / moves + 3.0 / std::floor(ref.dur[0] * 1000.0)) + 1.0;
  const double tol_p = ref.v_peak * shift + 2.0;
  Worst w{0, 0, tol_v, tol_p};
  auto s = start(r.plan);
  for (uint64_t t = 0;; ++t) {
    const auto k = kinematics(r.plan, s);
    const auto x = m::continuous_at(ref, static_cast<double>(t) / 1000.0);
    w.dv = std::max(w.dv, std::abs(static_cast<double>(k.vel_milli) / 1000.0 - x.v));
    w.dp = std::max(w.dp, std::abs(static_cast<double>(moves_at(r.plan, s)) - x.p));
    if (finished(r.plan, s)) break;
    s = step(r.plan, s);
  }
  return w;
}

TEST(ScurveReference, ThesisCasesWithinTickQuantisation) {
  for (uint32_t moves : {4000U, 2000U, 300U, 20U}) {
    const auto w = compare(moves, {1000, 2147483647, 400});
    EXPECT_LE(w.dv, w.tv) << moves;
    EXPECT_LE(w.dp, w.tp) << moves;
  }
  const auto w = compare(20000, {1000, 200, 400});  // with a constant-acceleration segment
  EXPECT_LE(w.dv, w.tv);
  EXPECT_LE(w.dp, w.tp);
}

TEST(ScurveReference, ContinuousModelMatchesTheThesis) {
  // The reference itself against seed §5.3.1/§5.4: 3.16228 s ramp, 736.8 moves/s short peak,
  // 7.162 s for 4000 moves.
  const auto full = m::continuous_plan(4000, 1000, 2147483647, 400);
  EXPECT_NEAR(full.dur[0] + full.dur[1] + full.dur[2], 3.16228, 1e-5);
  EXPECT_NEAR(full.total, 7.162, 5e-4);
  EXPECT_NEAR(m::continuous_at(full, full.total).p, 4000.0, 1e-6);
  const auto shrt = m::continuous_plan(2000, 1000, 2147483647, 400);
  EXPECT_NEAR(shrt.v_peak, 736.8, 0.05);
  EXPECT_NEAR(shrt.total, 5.43, 5e-3);
}

RC_GTEST_PROP(ScurveReference, RandomPlansWithinTickQuantisation, ()) {
  const auto moves = *rc::gen::inRange<uint32_t>(10, 5001);
  const auto v = *rc::gen::inRange<int32_t>(std::max<int32_t>(50, static_cast<int32_t>(moves / 10)), 5001);
  // Tj >= 5 ticks (a_max / J >= 5 ms, sqrt(v_max / J) >= 5 ms): below, Tj's rounding alone is 20 %.
  const auto j = *rc::gen::inRange<int32_t>(100, std::min(100001, v * 40000));
  const auto a = *rc::gen::inRange<int32_t>(std::max(1, (j + 199) / 200), 20001);
  const auto w = compare(moves, {v, a, j});
  RC_LOG() << "moves v a j " << moves << " " << v << " " << a << " " << j << " dv " << w.dv << "/" << w.tv << " dp " << w.dp << "/" << w.tp;
  RC_ASSERT(w.dv <= w.tv);
  RC_ASSERT(w.dp <= w.tp);
}

}  // namespace
