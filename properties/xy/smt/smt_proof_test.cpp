// The axis, timer and storage obligations through ctest (label proof): every one PROVED.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "models/xy/smt/modules.hpp"

namespace {

constexpr unsigned kTimeoutMs = 60000;

void prove_all(void (*add)(ap::model::smt::ObligationList&)) {
  ap::model::smt::ObligationList list;
  add(list);
  ASSERT_FALSE(list.empty());
  // A name prefix, like `axisproof prove --only`: for quick local runs and the proof mutants'
  // Killed-by checks (ci/mutants/README.md), so a prefix that names nothing fails.
  const char* only = std::getenv("AP_PROVE_ONLY");
  std::size_t selected = 0;
  for (const auto& o : list) {
    if (only != nullptr && o.name.rfind(only, 0) != 0) continue;
    ++selected;
    const auto r = ap::model::smt::run(o, kTimeoutMs);
    EXPECT_EQ(r.verdict, ap::model::smt::Verdict::Proved) << o.name << ": " << r.counterexample;
    std::printf("%-40s %-7s %.2f s\n", o.name.c_str(), ap::model::smt::verdict_name(r.verdict), r.seconds);
  }
  EXPECT_GT(selected, 0u) << "AP_PROVE_ONLY=" << only << " names no obligation of this module";
}

TEST(smt_proof, axis_obligations_proved) { prove_all(&ap::model::smt::add_axis_obligations); }
TEST(smt_proof, timer_obligations_proved) { prove_all(&ap::model::smt::add_timer_obligations); }
TEST(smt_proof, storage_obligations_proved) { prove_all(&ap::model::smt::add_storage_obligations); }

TEST(smt_proof, registry_contains_the_modules) {
  std::size_t axis = 0, timer = 0, storage = 0;
  for (const auto& o : ap::model::smt::xy_obligations()) {
    axis += o.name.rfind("axis.", 0) == 0 ? 1u : 0u;
    timer += o.name.rfind("timer.", 0) == 0 ? 1u : 0u;
    storage += o.name.rfind("storage.", 0) == 0 ? 1u : 0u;
  }
  EXPECT_GE(axis, 10u);
  EXPECT_EQ(timer, 3u);
  EXPECT_EQ(storage, 2u);
}

}  // namespace
