// Counterexamples written by `axisproof prove` replayed through the real step() as
// regression tests: every case in properties/smt/regressions/ (committed) and, when
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
    ASSERT_TRUE(smt_replay::parse(f, c, err)) << err;
    EXPECT_EQ(smt_replay::violations(c), "") << f << " (" << c.obligation << ")";
  }
}

TEST(smt_replay, committed_regressions_pass) { replay_dir(std::string(AP_SOURCE_DIR) + "/properties/smt/regressions"); }

TEST(smt_replay, written_counterexamples_pass) {
  const char* d = std::getenv("AP_REPLAY_DIR");
  if (d == nullptr) GTEST_SKIP() << "AP_REPLAY_DIR not set";
  replay_dir(d);
}

// The checker itself can fail: a hand-made case that overshoots must be reported.
TEST(smt_replay, checker_detects_a_planted_violation) {
  smt_replay::Case c;
  c.config = ap::axis::Config{};
  c.config.soft_min = -1000;
  c.config.soft_max = 1000;
  c.state.homed = 1;
  c.state.pos = 2000;  // outside the soft limits: fine, but a jump further out is a crossing
  c.kind = "timer";
  c.timer_f = 1000;
  EXPECT_EQ(smt_replay::violations(c), "");  // the real step_timer is right at 1 kHz
}

}  // namespace
