// The lockstep run the profiles' end-to-end layers share (sim/lockstep.hpp, sim/serve_loop.hpp),
// suite SimLockstep: the run's frame around a profile's board and PC side (the out folder, the
// report, the board's exit code, a refused period), the times it steps through, the fields of a
// board's env replies and the `violation INDEX` reply. The PC sides and boards themselves are
// tested with their profiles (properties/unit3/sim, properties/hc08/sim).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/lockstep.hpp"
#include "sim/serve_loop.hpp"

namespace fs = std::filesystem;
namespace sim = ap::sim;

namespace {

struct Options {
  std::string out_root;
  std::int64_t step_us = 10'000;
  std::optional<std::uint32_t> domain;
  bool join = false;
  std::ostream* log = nullptr;
};

struct Result {
  bool pass = false;
  std::vector<std::string> failures;
  std::uint32_t domain = 0;
  std::string out_dir;
};

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A run whose board exits with `rc` (or throws when rc < 0) and whose PC side reports `fail`.
Result run(const Options& o, int rc, const std::string& fail = "", std::string* board_out = nullptr) {
  return sim::run_lockstep(
      "test", "name", o,
      [&](const ap::dds::ParticipantPtr&, const std::string& out_dir, const std::atomic<bool>*) {
        if (board_out != nullptr) *board_out = out_dir;
        if (rc < 0) throw std::runtime_error("board broke");
        return rc;
      },
      [&](std::uint32_t) {
        Result r;
        if (!fail.empty()) r.failures.push_back(fail);
        return r;
      },
      [](const Result& r) { return std::string(r.pass ? "PASS" : "FAIL") + " " + std::to_string(r.failures.size()) + "\n"; });
}

}  // namespace

TEST(SimLockstep, TheRunWritesItsReportIntoAFreshFolder) {
  Options o;
  o.out_root = std::string(AP_BINARY_DIR) + "/sim-out/lockstep";
  const std::string dir = o.out_root + "/name";
  fs::create_directories(dir);
  std::ofstream(dir + "/stale.csv") << "old";
  std::string board_out;
  const Result r = run(o, 0, "", &board_out);
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.out_dir, dir);
  EXPECT_EQ(board_out, dir);
  EXPECT_FALSE(fs::exists(dir + "/stale.csv"));  // a stale trace must not pass for this run's
  EXPECT_EQ(slurp(dir + "/report.txt"), "PASS 0\n");
  const Result f = run(o, 0, "line 3: expect ...");
  EXPECT_FALSE(f.pass);
  EXPECT_EQ(slurp(dir + "/report.txt"), "FAIL 1\n");
}

TEST(SimLockstep, ABoardThatDoesNotShutDownCleanlyFailsTheRun) {
  Options o;
  std::ostringstream log;
  o.log = &log;
  const Result r = run(o, 2);
  EXPECT_FALSE(r.pass);
  ASSERT_EQ(r.failures.size(), 1U);
  EXPECT_EQ(r.failures[0], "the board did not shut down cleanly (code 2)");
  EXPECT_TRUE(r.out_dir.empty());  // no out_root: no outputs
  const Result t = run(o, -1);
  ASSERT_EQ(t.failures.size(), 1U);
  EXPECT_EQ(t.failures[0], "the board did not shut down cleanly (code 3)");
  EXPECT_EQ(log.str(), "test board: board broke\n");
}

TEST(SimLockstep, AJoinedRunHostsNoBoardAndWritesNothing) {
  Options o;
  o.out_root = std::string(AP_BINARY_DIR) + "/sim-out/lockstep-join";
  o.join = true;
  o.domain = 7;
  std::string board_out = "untouched";
  const Result r = run(o, 5, "", &board_out);
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.domain, 7U);
  EXPECT_TRUE(r.out_dir.empty());
  EXPECT_EQ(board_out, "untouched");
  EXPECT_FALSE(fs::exists(o.out_root + "/name/report.txt"));
}

TEST(SimLockstep, APeriodMustBePositive) {
  Options o;
  o.step_us = 0;
  try {
    run(o, 0);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "test run: the lockstep period must be positive");
  }
}

TEST(SimLockstep, TheTimesAreEveryPeriodAndTheEnd) {
  EXPECT_EQ(sim::lockstep_times(10, 35), (std::set<std::int64_t>{10, 20, 30, 35}));
  EXPECT_EQ(sim::lockstep_times(10, 30), (std::set<std::int64_t>{10, 20, 30}));
  EXPECT_EQ(sim::lockstep_times(50, 30), (std::set<std::int64_t>{30}));
}

TEST(SimLockstep, EnvFields) {
  const auto f = sim::env_fields("source=pc pulses=500 counter=-16 word v= big=1234567890123456789 n=12");
  EXPECT_EQ(f, (std::map<std::string, std::int64_t>{{"pulses", 500}, {"counter", -16}, {"n", 12}}));
}

TEST(SimLockstep, ViolationReplies) {
  const std::vector<std::string> v = {"first", "second"};
  EXPECT_EQ(sim::violation_reply(v, "0"), "first");
  EXPECT_EQ(sim::violation_reply(v, "1"), "second");
  EXPECT_EQ(sim::violation_reply(v, "2"), "error no violation 2");
  EXPECT_EQ(sim::violation_reply(v, ""), "error violation INDEX");
  EXPECT_EQ(sim::violation_reply(v, "-1"), "error violation INDEX");
  EXPECT_EQ(sim::violation_reply(v, "1234567890"), "error violation INDEX");
}
