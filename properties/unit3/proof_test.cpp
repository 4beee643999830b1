// The unit3 profile's proof obligations (models/smt/src/unit3_obligations.cpp), each PROVED.
#include <gtest/gtest.h>

#include "models/unit3/obligations.hpp"
#include "models/smt/obligation.hpp"

namespace {

TEST(Unit3Proofs, EveryObligationIsProved) {
  const auto list = ap::model::smt::unit3_obligations();
  ASSERT_EQ(list.size(), 5U);
  for (const auto& o : list) {
    const auto r = ap::model::smt::run(o, 60000);
    EXPECT_EQ(r.verdict, ap::model::smt::Verdict::Proved) << o.name << ": " << r.counterexample;
  }
}

}  // namespace
