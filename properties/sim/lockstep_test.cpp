// The lockstep run the profiles' end-to-end layers share (sim/lockstep.hpp, sim/serve_loop.hpp),
// suite SimLockstep: the run's frame around a profile's board and PC side (the out folder, the
// report, the board's exit code, a refused period, several numbered boards, a joined run's
// report), the times it steps through, the fields of a board's env replies and the
// `violation INDEX` reply. The PC sides and boards themselves are tested with their profiles
// (properties/<profile>/sim).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
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

// Several boards: each is served once with its own number and the run's out folder; a board
// that fails is named by its number.
TEST(SimLockstep, SeveralBoardsAreServedAndNamedByNumber) {
  Options o;
  o.out_root = std::string(AP_BINARY_DIR) + "/sim-out/lockstep-boards";
  std::ostringstream log;
  o.log = &log;
  std::mutex m;
  std::multiset<std::uint32_t> served;
  std::set<std::string> dirs;
  const sim::LockstepBoards boards{.count = 3, .numbered = true, .report_when_joined = false};
  const Result r = sim::run_lockstep(
      "test", "name", o, boards,
      [&](const ap::dds::ParticipantPtr&, std::uint32_t b, const std::string& out_dir, const std::atomic<bool>*) {
        {
          const std::lock_guard<std::mutex> g(m);
          served.insert(b);
          dirs.insert(out_dir);
        }
        if (b == 2) throw std::runtime_error("board broke");
        return b == 1 ? 2 : 0;
      },
      [](std::uint32_t) { return Result{}; },
      [](const Result& res) { return std::to_string(res.failures.size()) + "\n"; });
  EXPECT_EQ(served, (std::multiset<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(dirs, (std::set<std::string>{o.out_root + "/name"}));
  EXPECT_FALSE(r.pass);
  EXPECT_EQ(r.failures, (std::vector<std::string>{"board 1 did not shut down cleanly (code 2)",
                                                  "board 2 did not shut down cleanly (code 3)"}));
  EXPECT_EQ(log.str(), "board 2: board broke\n");
  EXPECT_EQ(slurp(o.out_root + "/name/report.txt"), "2\n");
}

// A joined run that keeps its report: out_root/NAME/report.txt is written, nothing is removed,
// no board is hosted, and the result names no out folder (the boards' outputs are elsewhere).
TEST(SimLockstep, AJoinedRunMayKeepItsReport) {
  Options o;
  o.out_root = std::string(AP_BINARY_DIR) + "/sim-out/lockstep-join-report";
  o.join = true;
  o.domain = 8;
  const std::string dir = o.out_root + "/name";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir + "/trace.csv") << "the boards' own";
  bool hosted = false;
  const sim::LockstepBoards boards{.count = 2, .numbered = true, .report_when_joined = true};
  const Result r = sim::run_lockstep(
      "test", "name", o, boards,
      [&](const ap::dds::ParticipantPtr&, std::uint32_t, const std::string&, const std::atomic<bool>*) {
        hosted = true;
        return 0;
      },
      [](std::uint32_t) { return Result{}; }, [](const Result& res) { return std::string(res.pass ? "PASS\n" : "FAIL\n"); });
  EXPECT_TRUE(r.pass);
  EXPECT_FALSE(hosted);
  EXPECT_EQ(r.domain, 8U);
  EXPECT_TRUE(r.out_dir.empty());
  EXPECT_EQ(slurp(dir + "/report.txt"), "PASS\n");
  EXPECT_EQ(slurp(dir + "/trace.csv"), "the boards' own");
}

// A PC side that throws: the boards are told to stop, joined, and the error goes on.
TEST(SimLockstep, APcSideThatThrowsStopsTheBoards) {
  Options o;
  std::atomic<int> stopped{0};
  const sim::LockstepBoards boards{.count = 2, .numbered = true, .report_when_joined = false};
  EXPECT_THROW(sim::run_lockstep(
                   "test", "name", o, boards,
                   [&](const ap::dds::ParticipantPtr&, std::uint32_t, const std::string&, const std::atomic<bool>* stop) {
                     while (!stop->load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
                     ++stopped;
                     return 1;
                   },
                   [](std::uint32_t) -> Result { throw std::runtime_error("bus failure"); },
                   [](const Result&) { return std::string(); }),
               std::runtime_error);
  EXPECT_EQ(stopped.load(), 2);
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
