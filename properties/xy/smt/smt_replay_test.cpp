// Counterexamples written by `axisproof prove` replayed through the real step() as
// regression tests: every case in properties/xy/smt/regressions/ (committed) and, when
// AP_REPLAY_DIR is set (e.g. to out/prove), every case there too.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "replay.hpp"

namespace {

void replay_dir(const std::string& dir) {
  for (const auto& f : smt_replay::case_files(dir)) {
    smt_replay::Case c;
    std::string err;
    ASSERT_TRUE(ap::model::smt::read_case(f, c, err)) << err;
    EXPECT_EQ(smt_replay::violations(c), "") << f << " (" << c.obligation << ")";
  }
}

TEST(smt_replay, committed_regressions_pass) { replay_dir(std::string(AP_SOURCE_DIR) + "/properties/xy/smt/regressions"); }

TEST(smt_replay, written_counterexamples_pass) {
  const char* d = std::getenv("AP_REPLAY_DIR");
  if (d == nullptr) GTEST_SKIP() << "AP_REPLAY_DIR not set";
  replay_dir(d);
}

// That the checks can fail is shown by the proof mutants (docs/proofs.md): the cases in
// regressions/ were written by FAILED obligations on mutated builds and fail there.
TEST(smt_replay, timer_case_passes_on_real_code) {
  smt_replay::Case c;
  c.kind = "timer";
  for (unsigned f : {1U, 610U, 1220U, 1221U, 51200U, 1000000U, 40000000U}) {
    c.timer_f = f;
    EXPECT_EQ(smt_replay::violations(c), "") << f;
  }
}

}  // namespace
