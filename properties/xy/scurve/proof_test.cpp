// The S-curve's proof obligations (models/smt/src/scurve_obligations.cpp), each Proved, and the
// conformance of the terms they are stated over with the core's step() (docs/scurve.md "Proof").
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <string>
#include <vector>

#include "core/xy/scurve/profile.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/smt/obligation.hpp"


namespace {

namespace smt = ap::model::smt;
using namespace ap::xy_scurve;

TEST(ScurveProof, EveryObligationIsProved) {
  smt::ObligationList list;
  smt::add_scurve_obligations(list);
  ASSERT_EQ(list.size(), 10U);
  for (const auto& o : list) {
    EXPECT_EQ(o.name.rfind("scurve.", 0), 0U) << o.name;
    const auto r = smt::run(o, 60000);
    EXPECT_EQ(r.verdict, smt::Verdict::Proved) << o.name << ": " << r.counterexample;
    RecordProperty(o.name, std::to_string(r.seconds));
  }
}

// The terms on concrete values of a state the core reached, against the core's step().
RC_GTEST_PROP(ScurveProof, StepTermsMatchTheCore, ()) {
  const auto moves = *rc::gen::inRange<uint32_t>(1, 3001);
  const auto v = *rc::gen::inRange<int32_t>(std::max<int32_t>(20, static_cast<int32_t>(moves / 10)), 20001);
  const auto j = *rc::gen::inRange<int32_t>(1000, std::min<int32_t>(100000000, v * 1000) + 1);
  const auto a = *rc::gen::inRange<int32_t>((j + 999) / 1000, std::max((j + 999) / 1000, 100000) + 1);
  const auto r = plan(moves, Limits{v, a, j});
  RC_ASSERT(r.error == Error::None);
  const auto at = *rc::gen::inRange<uint64_t>(0, r.plan.total_ticks + 2);
  auto s = start(r.plan);
  for (uint64_t i = 0; i < at; ++i) s = step(r.plan, s);
  const auto n = step(r.plan, s);

  z3::context c;
  constexpr unsigned w = 64;
  std::vector<z3::expr> len;
  for (auto l : r.plan.len) len.push_back(c.bv_val(static_cast<uint64_t>(l), w));
  const auto t = smt::scurve_step_terms(
      c, {c.bv_val(static_cast<unsigned>(s.seg), 3), c.bv_val(static_cast<uint64_t>(s.tick), w), c.bv_val(s.k.a, w), c.bv_val(s.k.v2, w)},
      len);
  const auto num = [](const z3::expr& e) { return e.simplify().get_numeral_uint64(); };
  RC_ASSERT(num(t[0]) == uint64_t{n.seg});
  RC_ASSERT(num(t[1]) == uint64_t{n.tick});
  RC_ASSERT(static_cast<int64_t>(num(t[2])) == n.k.a);
  RC_ASSERT(static_cast<int64_t>(num(t[3])) == n.k.v2);
}

}  // namespace
