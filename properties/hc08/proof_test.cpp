// The hc08 profile's proof obligations (models/smt/src/hc08_obligations.cpp), each PROVED, and
// the ramp arithmetic they state checked against the core's (core/hc08_timer) on every period
// the ramp can hold, so the proofs speak about the code that runs.
#include <gtest/gtest.h>

#include <cstdint>

#include "core/hc08_timer/timer.hpp"
#include "models/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace {

namespace smt = ap::model::smt;
namespace t = ap::hc08_timer;
using ap::hc08_drive::Drive;

TEST(Hc08Proofs, EveryObligationIsProved) {
  const auto list = smt::hc08_obligations();
  ASSERT_EQ(list.size(), 5U);
  for (const auto& o : list) {
    const auto r = smt::run(o, 60000);
    EXPECT_EQ(r.verdict, smt::Verdict::Proved) << o.name << ": " << r.counterexample;
  }
}

std::uint64_t eval(const z3::expr& e) { return e.simplify().get_numeral_uint64(); }

TEST(Hc08Proofs, TheStatedRampIsTheCoresOnEveryPeriod) {
  z3::context& c = smt::shared_context();
  for (const Drive d : {Drive::Full, Drive::Half}) {
    const std::uint16_t start = t::tmod_at_hz(t::start_hz(d));
    const std::uint16_t fastest = t::tmod_at_hz(t::max_hz(d));
    for (std::uint32_t now = fastest; now <= start; now += 7) {
      ASSERT_EQ(eval(smt::hc08_steps_to_start(c, c.bv_val(now, 32), d)), t::steps_to_start(static_cast<std::uint16_t>(now), d));
      for (std::uint32_t target = fastest; target <= start; target += 97) {
        for (const bool stopping : {false, true}) {
          const auto core = t::ramp_step(static_cast<std::uint16_t>(now), static_cast<std::uint16_t>(target), stopping, d);
          const auto stated = eval(smt::hc08_ramp_step_term(c, c.bv_val(now, 32), c.bv_val(target, 32), c.bool_val(stopping), d));
          ASSERT_EQ(stated, core) << now << " " << target << " " << stopping;
        }
      }
    }
  }
}

}  // namespace
