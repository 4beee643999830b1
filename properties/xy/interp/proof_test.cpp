// The interp obligations (models/smt/src/interp_obligations.cpp), each PROVED, and the step they
// state checked against the core's Line::axis_step and Line::next (core/xy/interp/line.hpp), so the
// proofs speak about the code that runs (docs/interpolation.md "Proof").
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "core/xy/interp/line.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/smt/obligation.hpp"


namespace {

namespace smt = ap::model::smt;
using ap::xy_interp::Line;

TEST(InterpProof, EveryObligationIsProved) {
  smt::ObligationList list;
  smt::add_interp_obligations(list);
  ASSERT_EQ(list.size(), 5U);
  for (const auto& o : list) {
    EXPECT_EQ(o.name.rfind("interp.bresenham.", 0), 0U) << o.name;
    const auto r = smt::run(o, 60000);
    EXPECT_EQ(r.verdict, smt::Verdict::Proved) << o.name << ": " << r.counterexample;
    std::printf("%-44s %-7s %.2f s\n", o.name.c_str(), smt::verdict_name(r.verdict), r.seconds);
  }
}

struct Stated {
  int32_t err;
  bool moves;
};

Stated stated(int32_t n, int32_t a, int32_t err) {
  z3::context& c = smt::shared_context();
  const auto v = [&](int32_t x) { return c.bv_val(x, 32); };
  const z3::expr e = smt::interp_axis_step_err(c, v(n), v(a), v(err)).simplify();
  const z3::expr m = smt::interp_axis_step_moves(c, v(n), v(a), v(err)).simplify();
  return {static_cast<int32_t>(e.get_numeral_int64() > INT32_MAX ? e.get_numeral_int64() - (int64_t{1} << 32)
                                                                   : e.get_numeral_int64()),
          m.is_true()};
}

RC_GTEST_PROP(InterpProof, StatedStepIsTheCoresOnRandomStates, ()) {
  // States inside the obligations' precondition: n in [1, 2^24], a in [0, n], err in [-n, n).
  const int32_t n = *rc::gen::inRange<int32_t>(1, (1 << 24) + 1);
  const int32_t a = *rc::gen::oneOf(rc::gen::just(0), rc::gen::just(n), rc::gen::inRange<int32_t>(0, n + 1));
  const int32_t err = *rc::gen::oneOf(rc::gen::just(-n), rc::gen::just(n - 1), rc::gen::inRange<int32_t>(-n, n));
  const auto core = Line::axis_step(n, a, err);
  const Stated s = stated(n, a, err);
  RC_ASSERT(core.err == s.err);
  RC_ASSERT(core.moves == s.moves);
}

RC_GTEST_PROP(InterpProof, StatedStepFollowsWholeLines, ()) {
  // Line::next() on a 3-axis line moves axis i exactly when the stated step says so, from err = 0.
  const std::array<int32_t, 3> d{*rc::gen::inRange(-150, 151), *rc::gen::inRange(-150, 151), *rc::gen::inRange(-150, 151)};
  Line l{d};
  const auto n = static_cast<int32_t>(l.moves());
  std::array<int32_t, 3> err{0, 0, 0};
  while (!l.done()) {
    const auto m = l.next();
    for (std::size_t i = 0; i < 3; ++i) {
      const Stated s = stated(n, std::abs(d[i]), err[i]);
      RC_ASSERT((m[i] != 0) == s.moves);
      err[i] = s.err;
    }
  }
}

}  // namespace
