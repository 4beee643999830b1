// The hc08 profile end to end (docs/hc08-sim.md), suites Hc08Sim*:
//   Hc08SimScenario/Bundled.Passes/NAME  every scenarios/hc08/*.scn passes over the DDS bus
//   Hc08SimVerdict.*                     a wrong expectation of each kind fails the run
//   Hc08SimParser.*                      the language's errors name file:line
//   Hc08SimSafety.*                      each safety property catches a planted violation in a
//                                        hand-made trace, and the real unit's trace is clean
//   Hc08SimBoard.*                       the time model, the key scan, determinism, and the
//                                        outputs (the VCD's four phase lines match the run)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "profile_sim_support.hpp"
#include "sim/hc08/hc08.hpp"

namespace fs = std::filesystem;
namespace h = ap::sim::hc08;

namespace {

using ap::sim::test::count_of;
using ap::sim::test::says;
using ap::sim::test::slurp;

std::vector<std::string> bundled() { return ap::sim::test::bundled(AP_HC08_SCENARIOS); }

std::string out_root() { return std::string(AP_BINARY_DIR) + "/sim-out/hc08"; }

h::RunResult run(const h::Scenario& s, const std::string& root = out_root()) {
  h::RunOptions o;
  o.out_root = root;
  return h::run_scenario(s, o);
}

// The scenario's keys straight into a Board, without the bus.
void drive(h::Board& b, const h::Scenario& s) {
  for (const h::Action& a : s.actions) {
    b.advance_to(a.t_us);
    ASSERT_EQ(b.press(a.code, a.hold_ms, a.bounce), "") << "line " << a.line;
  }
  b.advance_to(s.duration_us);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
class Bundled : public ::testing::TestWithParam<std::string> {};

TEST_P(Bundled, Passes) {
  const h::Scenario s = h::parse_file(std::string(AP_HC08_SCENARIOS) + "/" + GetParam() + ".scn");
  const h::RunResult r = run(s);
  std::cout << h::format_report(s, r);
  EXPECT_TRUE(r.pass);
  EXPECT_TRUE(r.failures.empty());
  EXPECT_EQ(r.passed.size(), s.expectations.size());
  EXPECT_GE(s.expectations.size(), 10U);
  EXPECT_EQ(r.vtime_us, s.duration_us);
  // Every event went through the safety checker: at least every step and every press.
  EXPECT_GE(r.events, r.steps + r.presses);
  for (const char* f : {"trace.csv", "waveforms.vcd", "plots.svg", "report.txt"}) {
    EXPECT_TRUE(fs::is_regular_file(r.out_dir + "/" + f)) << f;
  }
}

INSTANTIATE_TEST_SUITE_P(Hc08SimScenario, Bundled, ::testing::ValuesIn(bundled()), ap::sim::test::test_name);

TEST(Hc08SimScenario, AtLeastSevenAreBundled) { EXPECT_GE(bundled().size(), 7U); }

// ---------------------------------------------------------------------------------------------
// The expectations can fail: mode B's 90° (10 steps at 40 Hz, from 320 ms) with each kind of
// expectation made wrong, each failing alone and naming its line.
TEST(Hc08SimVerdict, EveryKindOfExpectationCanFail) {
  const std::string head = "scenario verdict\nduration 1 s\nat 100 ms press minus\nat 300 ms press set\n";
  const std::vector<std::string> wrong = {
      "expect end steps == 9",
      "expect at 344 ms steps == 1",                 // the first step is at 345 ms
      "expect at 119 ms mode == B",                  // 20 scans: not before 120 ms
      "expect end coils == 0011",
      "expect end port == 0x18",
      "expect end value == 810",
      "expect end angle != 900",
      "expect end direction == l",
      "expect end dir == l",
      "expect at 400 ms frequency == 280",
      "expect between 300 ms and end frequency < 40",  // every step is at 40 Hz
      "expect between 0 s and end running == 0",       // it ran from 320 to 570 ms
      "expect by 500 ms running == 0",                 // still running at 500 ms
      "expect change between 300 ms and end steps == 11",
      "expect end presses == 1",
      "expect end unknown > 0",
      "expect end drive == 8",
      "expect end indicator == 2",
      "expect end error == 1",
      "expect end point == 0",
      "expect at 400 ms period == 61439",
      "expect end position == -20",
  };
  for (const std::string& w : wrong) {
    const h::Scenario s = h::parse(head + w + "\n", "verdict.scn");
    const h::RunResult r = run(s, "");
    EXPECT_FALSE(r.pass) << w;
    ASSERT_EQ(r.failures.size(), 1U) << w;
    EXPECT_NE(r.failures[0].find("line 5"), std::string::npos) << r.failures[0];
  }
  // The same kinds made right pass: the failures above are the expectations', not the run's.
  const h::Scenario ok = h::parse(head +
                                      "expect end steps == 10\nexpect at 345 ms steps == 1\nexpect at 120 ms mode == B\n"
                                      "expect between 345 ms and end frequency == 40\nexpect by 600 ms running == 0\n"
                                      "expect change between 300 ms and end steps == 10\nexpect end coils == 1100\n",
                                  "verdict.scn");
  const h::RunResult r = run(ok, "");
  EXPECT_TRUE(r.pass) << h::format_report(ok, r);
  EXPECT_EQ(r.steps, 10U);
  EXPECT_EQ(r.presses, 2U);
}

// ---------------------------------------------------------------------------------------------
namespace {

void parse(const std::string& text, const std::string& file) { (void)h::parse(text, file); }

}  // namespace

TEST(Hc08SimParser, ReadsEveryStatement) {
  const h::Scenario s = h::parse(
      "# comment\n"
      "scenario all_of_it   # trailing comment\n"
      "title \"T \\\"q\\\" # not a comment\"\n"
      "duration 2.5 s\n"
      "at 1 s press plus x3 hold 30 ms\n"
      "at 10ms press SA1\n"
      "at 500 ms press minus bounce\n"
      "at 0.6 s press 0x2D hold 11 ms bounce\n"
      "expect at 1 s value == 900\n"
      "expect end mode == B\n"
      "expect at end coils == 1001\n"
      "expect by 2 s running == 0\n"
      "expect between 0.5 s and 1 s frequency <= 800\n"
      "expect change between 1 s and end steps >= -3\n"
      "expect at 1 s port == 0x48\n"
      "expect at 1 s direction == l\n"
      "expect at 1 s drive == 8\n",
      "all.scn");
  EXPECT_EQ(s.name, "all_of_it");
  EXPECT_EQ(s.title, "T \"q\" # not a comment");
  EXPECT_EQ(s.duration_us, 2'500'000);
  ASSERT_EQ(s.actions.size(), 6U);
  // In time order; x3 expanded one every hold + 40 ms.
  EXPECT_EQ(s.actions[0].code, ap::hc08_board::key_code(1));
  EXPECT_EQ(s.actions[0].t_us, 10'000);
  EXPECT_EQ(s.actions[0].hold_ms, 60U);
  EXPECT_EQ(s.actions[1].code, 0x2E);  // minus: SA2
  EXPECT_TRUE(s.actions[1].bounce);
  EXPECT_EQ(s.actions[2].code, 0x2D);
  EXPECT_EQ(s.actions[2].hold_ms, 11U);
  EXPECT_EQ(s.actions[3].code, 0x2B);  // plus: SA8
  EXPECT_EQ(s.actions[3].t_us, 1'000'000);
  EXPECT_EQ(s.actions[4].t_us, 1'070'000);
  EXPECT_EQ(s.actions[5].t_us, 1'140'000);
  EXPECT_EQ(s.actions[5].line, 5);
  ASSERT_EQ(s.expectations.size(), 9U);
  EXPECT_EQ(s.expectations[0].kind, h::ExpectKind::At);
  EXPECT_EQ(s.expectations[0].value, 900);
  EXPECT_EQ(s.expectations[1].t_us, 2'500'000);
  EXPECT_EQ(s.expectations[1].value, 1);
  EXPECT_EQ(s.expectations[2].value, 0b1001);
  EXPECT_EQ(s.expectations[3].kind, h::ExpectKind::Throughout);
  EXPECT_EQ(s.expectations[3].t0_us, 2'000'000);
  EXPECT_EQ(s.expectations[3].t_us, 2'500'000);
  EXPECT_EQ(s.expectations[4].kind, h::ExpectKind::Throughout);
  EXPECT_EQ(s.expectations[4].op, h::Op::Le);
  EXPECT_EQ(s.expectations[5].kind, h::ExpectKind::Change);
  EXPECT_EQ(s.expectations[5].value, -3);
  EXPECT_EQ(s.expectations[6].value, 0x48);
  EXPECT_EQ(s.expectations[7].value, -1);
  EXPECT_EQ(s.expectations[8].value, 8);
  EXPECT_EQ(s.expectations[8].text, "expect at 1 s drive == 8");
}

TEST(Hc08SimParser, ErrorsNameTheFileAndLine) {
  const std::string ok = "scenario s\nduration 1 s\n";  // lines 1-2
  ap::sim::test::expect_errors(parse, {
      {ok + "title \"abc\n", 3, "unterminated string"},
      {ok + "at 10 parsecs press set\n", 3, "bad time"},
      {ok + "at 10 ms press jump\n", 3, "unknown key"},
      {ok + "\n\nat 10 ms press SA13\n", 5, "unknown key"},
      {ok + "at 10 ms press 0x00\n", 3, "scan of no key"},
      {ok + "at 10 ms push set\n", 3, "expected 'press'"},
      {ok + "at 10 ms press set x0\n", 3, "x0 presses nothing"},
      {ok + "at 10 ms press set hold 0.5 ms\n", 3, "whole ms"},
      {ok + "at 10 ms press set hold 10 ms bounce\n", 3, "longer than 10 ms"},
      {ok + "at 10 ms press set sideways\n", 3, "unexpected 'sideways'"},
      {ok + "at 10 ms press set\nat 50 ms press plus\n", 4, "still held"},
      {ok + "at 900 ms press set x2\n", 3, "after the end"},
      {ok + "at 1 s press set\n", 3, "after the end"},
      {ok + "expect at 2 s steps == 1\n", 3, "after the end"},
      {ok + "expect end steps =< 1\n", 3, "unknown comparison"},
      {ok + "expect end speed == 1\n", 3, "unknown quantity"},
      {ok + "expect end mode == C\n", 3, "mode is A or B"},
      {ok + "expect end drive == 6\n", 3, "drive is 4 or 8"},
      {ok + "expect end coils == 0x3\n", 3, "four binary digits"},
      {ok + "expect end port == 300\n", 3, "port is a byte"},
      {ok + "expect end direction == up\n", 3, "r or l"},
      {ok + "expect end running == 2\n", 3, "0 or 1"},
      {ok + "expect between 0.5 s and 0.2 s steps == 1\n", 3, "T1 < T2"},
      {ok + "expect change between 0.1 s and end mode == 1\n", 3, "takes a count"},
      {ok + "expect by 1 s running == 0\n", 3, "window is empty"},
      {ok + "expect sometime steps == 1\n", 3, "unknown expectation"},
      {ok + "expect end steps == 1 extra\n", 3, "unexpected 'extra'"},
      {ok + "duration 2 s\n", 3, "second 'duration'"},
      {ok + "duration 1.5 ms\n", 3, "second 'duration'"},
      {"scenario s\nduration 1.5 ms\n", 2, "whole ms"},
      {"duration 1 s\nscenario bad/name\n", 2, "letters, digits"},
      {"scenario s\n", 1, "no 'duration'"},
      {ok + "launch\n", 3, "unknown statement"},
      {ok + "title \"\\q\"\n", 3, "escapes only"},
  });
}

// Times in exact microseconds: properties/sim/scenario_text_test.cpp. Here, that the hc08
// language reads them in its dialect (up to a day of virtual time, 15 characters).
TEST(Hc08SimParser, TimesInTheHc08Dialect) {
  std::int64_t us = 0;
  EXPECT_TRUE(h::parse_time("1.25", "s", us));
  EXPECT_EQ(us, 1'250'000);
  EXPECT_FALSE(h::parse_time("0.0000001", "s", us));  // finer than 1 us
  EXPECT_TRUE(h::parse_time("86400", "s", us));
  EXPECT_EQ(us, 86'400'000'000LL);
  EXPECT_FALSE(h::parse_time("86400.000001", "s", us));
  EXPECT_FALSE(h::parse_time("0000000000000001", "us", us));
}

TEST(Hc08SimParser, KeyNames) {
  std::uint8_t c = 0;
  ASSERT_TRUE(h::key_of("set", c));
  EXPECT_EQ(c, 0x2D);
  ASSERT_TRUE(h::key_of("left", c));
  EXPECT_EQ(c, 0x4D);
  ASSERT_TRUE(h::key_of("right", c));
  EXPECT_EQ(c, 0x1D);
  ASSERT_TRUE(h::key_of("plus", c));
  EXPECT_EQ(c, 0x2B);
  ASSERT_TRUE(h::key_of("minus", c));
  EXPECT_EQ(c, 0x2E);
  ASSERT_TRUE(h::key_of("SA12", c));
  EXPECT_EQ(c, 0x17);
  EXPECT_FALSE(h::key_of("SA0", c));
  EXPECT_FALSE(h::key_of("Set", c));
}

// ---------------------------------------------------------------------------------------------
// Hand-made traces of the phase lines: a motion of steps with given intervals in BUSCLK ticks.
namespace {

constexpr std::array<std::uint8_t, 8> kHalf = {0b0001, 0b0011, 0b0010, 0b0110, 0b0100, 0b1100, 0b1000, 0b1001};

struct Trace {
  std::vector<h::Sample> s;
  std::int64_t t = 0;
  int pos = 1;  // 0011, the power-up pattern
  bool half = false;
  bool running = false;
  Trace() { s.push_back({0, false, kHalf[1], false, false}); }
  void start(std::int64_t after_ticks = 1000) {
    t += after_ticks * h::kUnitsPerTick;
    running = true;
    s.push_back({t, false, kHalf[static_cast<std::size_t>(pos)], half, true});
  }
  // One step `ticks` after the previous event, `dir` (+1/-1) one step of the drive type.
  void step(std::int64_t ticks, int dir = 1, bool last = false) {
    t += ticks * h::kUnitsPerTick;
    pos = ((pos + dir * (half ? 1 : 2)) % 8 + 8) % 8;
    if (last) running = false;
    s.push_back({t, true, kHalf[static_cast<std::size_t>(pos)], half, running});
  }
  // A raw sample (a planted pattern).
  void raw(std::int64_t ticks, bool is_step, std::uint8_t coils, bool run) {
    t += ticks * h::kUnitsPerTick;
    running = run;
    s.push_back({t, is_step, coils, half, run});
  }
  // The documented ramp in full step: 8 777 ticks down by 64 to `top`, `hold` steps there,
  // and back up to 8 777, the last step there.
  void ramp(std::int64_t top, int hold, int dir = 1) {
    std::int64_t p = 8777;
    for (; p > top; p = std::max(top, p - 64)) step(p, dir);
    for (int i = 0; i < hold; ++i) step(top, dir);
    for (p = top + 64; p < 8777; p += 64) step(p, dir);
    step(8777, dir, true);
  }
  std::vector<std::string> check() const {
    h::SafetyChecker c;
    for (const h::Sample& x : s) c.check(x);
    return c.violations();
  }
};

}  // namespace

TEST(Hc08SimSafety, TheDocumentedRampAndReversalAreClean) {
  Trace tr;
  tr.start();
  tr.ramp(3072, 20);  // 280 -> 800 Hz (3 072 ticks exactly: the maximum is allowed)
  tr.start();
  tr.ramp(5585, 5, -1);  // the other way after a stop at 280 Hz
  // A reversal while running, at the start frequency: the first step back is a start (8 777),
  // then up the other way.
  tr.start();
  tr.step(8777);
  tr.step(8713);
  tr.step(8777);
  tr.step(8777, -1);
  tr.step(8713, -1);
  tr.step(8777, -1, true);
  // Half step: 560 -> 1700 Hz (1 446 ticks is 1699.6 Hz) and back.
  Trace half;
  half.half = true;
  half.start();
  for (std::int64_t p = 4389; p > 1446; p = std::max<std::int64_t>(1446, p - 64)) half.step(p);
  half.step(1446);
  for (std::int64_t p = 1446 + 64; p < 4389; p += 64) half.step(p);
  half.step(4389, 1, true);
  EXPECT_TRUE(tr.check().empty()) << ::testing::PrintToString(tr.check());
  EXPECT_TRUE(half.check().empty()) << ::testing::PrintToString(half.check());
}

TEST(Hc08SimSafety, MaxfreqCatchesAStepAboveTheMaximum) {
  Trace tr;
  tr.start();
  for (std::int64_t p = 8777;; p = std::max<std::int64_t>(3071, p - 64)) {  // 800.3 Hz at the end
    tr.step(p);
    if (p == 3071) break;
  }
  EXPECT_TRUE(says(tr.check(), "above the maximum 800 Hz")) << ::testing::PrintToString(tr.check());
  Trace half;
  half.half = true;
  half.start();
  for (std::int64_t p = 4389;; p = std::max<std::int64_t>(1445, p - 64)) {  // 1700.8 Hz at the end
    half.step(p);
    if (p == 1445) break;
  }
  EXPECT_TRUE(says(half.check(), "above the maximum 1700 Hz")) << ::testing::PrintToString(half.check());
}

TEST(Hc08SimSafety, StartCatchesAFlyingStart) {
  Trace tr;
  tr.start();
  tr.step(8776);  // 280.03 Hz: one tick short of the start period
  EXPECT_TRUE(says(tr.check(), "a motion started at 280.0 Hz, above the start frequency")) << ::testing::PrintToString(tr.check());
  Trace ok;
  ok.start();
  ok.step(61440, 1, true);  // 40 Hz, below the start frequency: at once
  EXPECT_TRUE(ok.check().empty()) << ::testing::PrintToString(ok.check());
}

TEST(Hc08SimSafety, RampCatchesAPeriodJumpAboveTheStartFrequency) {
  Trace tr;
  tr.start();
  tr.step(8777);
  tr.step(8700);  // 77 ticks
  EXPECT_TRUE(says(tr.check(), "the period went from 8777.00 to 8700.00 ticks")) << ::testing::PrintToString(tr.check());
  // Slower than the start frequency the period may jump (a slow speed runs at once).
  Trace ok;
  ok.start();
  ok.step(61440);
  ok.step(8713);  // from 40 Hz: counted as from 8 777
  ok.step(8777, 1, true);
  EXPECT_TRUE(ok.check().empty()) << ::testing::PrintToString(ok.check());
}

TEST(Hc08SimSafety, ReverseCatchesADirectionChangeAboveTheStartFrequency) {
  Trace tr;
  tr.start();
  tr.step(8777);
  tr.step(8713);
  tr.step(8649);
  tr.step(8585, -1);  // both neighbours above 280 Hz
  EXPECT_TRUE(says(tr.check(), "the direction reversed between steps at 284.1 Hz and 286.3 Hz")) << ::testing::PrintToString(tr.check());
}

TEST(Hc08SimSafety, ReverseCatchesAFirstStepBackAboveTheStartFrequency) {
  // Down to 280 Hz, but the first step the other way already ramped (282 Hz): a reversal is a
  // start, and a start is at or below the start frequency (docs/hc08.md "Ramp").
  Trace tr;
  tr.start();
  tr.step(8777);
  tr.step(8713, -1);
  EXPECT_TRUE(says(tr.check(), "the direction reversed between steps at 280.0 Hz and 282.1 Hz")) << ::testing::PrintToString(tr.check());
}

TEST(Hc08SimSafety, StopCatchesAStopFromSpeed) {
  Trace tr;
  tr.start();
  tr.step(8777);
  tr.step(8713);
  tr.step(8649, 1, true);  // the last step at 284 Hz
  EXPECT_TRUE(says(tr.check(), "the motor stopped after a step at 284.1 Hz")) << ::testing::PrintToString(tr.check());
  // The timer stopped between steps (no step ends the motion): judged on the last step.
  Trace between;
  between.start();
  between.step(8777);
  between.step(8713);
  between.raw(100, false, kHalf[5], false);
  EXPECT_TRUE(says(between.check(), "the motor stopped after a step at 282.1 Hz")) << ::testing::PrintToString(between.check());
}

TEST(Hc08SimSafety, CoilsCatchBadPatternsAndBadSteps) {
  Trace opposite;
  opposite.start();
  opposite.raw(8777, true, 0b0101, true);
  EXPECT_TRUE(says(opposite.check(), "coils 0101: two opposite coils energised")) << ::testing::PrintToString(opposite.check());
  Trace three;
  three.start();
  three.raw(8777, true, 0b0111, true);
  EXPECT_TRUE(says(three.check(), "coils 0111: two opposite coils")) << ::testing::PrintToString(three.check());
  Trace none;
  none.raw(10, false, 0b0000, false);
  EXPECT_TRUE(says(none.check(), "coils 0000: not a rest position")) << ::testing::PrintToString(none.check());
  // A full step that moves half a step, and one that does not move.
  Trace halfway;
  halfway.start();
  halfway.raw(8777, true, 0b0010, true);  // 0011 -> 0010
  EXPECT_TRUE(says(halfway.check(), "a full step went 0011 -> 0010 (1 half steps)")) << ::testing::PrintToString(halfway.check());
  Trace still;
  still.start();
  still.raw(8777, true, 0b0011, true);
  EXPECT_TRUE(says(still.check(), "a full step went 0011 -> 0011 (0 half steps)")) << ::testing::PrintToString(still.check());
  // A half step that moves a full step.
  Trace hs;
  hs.half = true;
  hs.start();
  hs.raw(8777, true, 0b0110, true);
  EXPECT_TRUE(says(hs.check(), "a half step went 0011 -> 0110 (2 half steps)")) << ::testing::PrintToString(hs.check());
  // The coils change between steps while running.
  Trace glitch;
  glitch.start();
  glitch.step(8777);
  glitch.raw(10, false, 0b1100, true);
  EXPECT_TRUE(says(glitch.check(), "the coils changed between steps while running")) << ::testing::PrintToString(glitch.check());
  // At rest only a drive change's half step forward: 0010 -> 0011 is allowed, 0011 -> 0001 not.
  Trace rest;
  rest.half = true;
  rest.raw(10, false, 0b0010, false);  // +1 from 0011
  EXPECT_TRUE(rest.check().empty()) << ::testing::PrintToString(rest.check());
  rest.raw(10, false, 0b0011, false);  // -1
  EXPECT_TRUE(says(rest.check(), "the coils changed at rest by -1 half steps")) << ::testing::PrintToString(rest.check());
  // A step while the timer is stopped.
  Trace stray;
  stray.raw(8777, true, 0b0110, false);
  EXPECT_TRUE(says(stray.check(), "a step while the timer was stopped")) << ::testing::PrintToString(stray.check());
}

TEST(Hc08SimSafety, TheRealUnitsTraceIsCleanAndAPlantedFaultInItIsNot) {
  const h::Scenario s = h::parse_file(std::string(AP_HC08_SCENARIOS) + "/mode_a_reversal.scn");
  h::Board b(h::BoardOptions{});
  drive(b, s);
  EXPECT_TRUE(b.safety().violations().empty()) << ::testing::PrintToString(b.safety().violations());
  EXPECT_EQ(b.safety().steps(), 667U);
  EXPECT_EQ(b.safety().events(), b.rows().size());
  std::vector<h::Sample> samples;
  for (const h::Row& r : b.rows()) samples.push_back({r.t, r.event == h::Event::Step, r.coils, r.half, r.running});
  // Planted: the unit reverses at full speed, as one without the ramp down would: the direction
  // of every step after the first one at 440 Hz past the key at 1720 ms is flipped (each
  // pattern mirrored about the pattern before the flip).
  auto planted = samples;
  std::size_t flip = 0;
  for (std::size_t i = 1; i < planted.size(); ++i) {
    if (planted[i].step && planted[i].t > 1720 * h::kUnitsPerMs) {
      flip = i;
      break;
    }
  }
  ASSERT_GT(flip, 0U);
  const int pivot = *h::half_position(planted[flip - 1].coils);
  for (std::size_t i = flip; i < planted.size(); ++i) {
    const int p = *h::half_position(samples[i].coils);
    planted[i].coils = kHalf[static_cast<std::size_t>(((2 * pivot - p) % 8 + 8) % 8)];
  }
  h::SafetyChecker c;
  for (const h::Sample& x : planted) c.check(x);
  EXPECT_TRUE(says(c.violations(), "the direction reversed between steps at 440.0 Hz and 440.0 Hz")) << ::testing::PrintToString(c.violations());
}

// ---------------------------------------------------------------------------------------------
TEST(Hc08SimBoard, AKeyCountsAtTheTwentiethScanAndTheTimerRunsInBusclkTicks) {
  h::Board b(h::BoardOptions{});
  b.advance_to(100'000);
  ASSERT_EQ(b.press(ap::hc08_board::key_code(5), 60, false), "");  // SET: mode A, 1.00 rev/s
  EXPECT_NE(b.press(ap::hc08_board::key_code(8), 60, false), "");  // one key at a time
  b.advance_to(119'999);
  EXPECT_FALSE(b.unit().timer_running());
  b.advance_to(120'000);
  ASSERT_TRUE(b.unit().timer_running());
  // 40 Hz: 61 440 ticks = exactly 25 ms.
  b.advance_to(144'999);
  EXPECT_EQ(b.quantity(h::Quantity::Steps), 0);
  b.advance_to(145'000);
  EXPECT_EQ(b.quantity(h::Quantity::Steps), 1);
  EXPECT_EQ(b.quantity(h::Quantity::Period), 61440);
  EXPECT_EQ(b.rows().back().t, 145 * h::kUnitsPerMs);
  EXPECT_EQ(b.env("get steps"), "1");
  EXPECT_EQ(b.env("get coils"), "6");  // 0110
  EXPECT_EQ(b.env("range steps 0 1"), "min=0 max=1 samples=4 equal=1");  // init, scan, key, step
  EXPECT_NE(b.env("get speed").rfind("error", 0), std::string::npos);
  EXPECT_EQ(b.env("summary"), "t_us=145000 events=4 steps=1 presses=1 dropped=0 violations=0");
  // The SET key is held for the scans 101..160: another key only from the scan at 161 ms.
  b.advance_to(159'999);
  EXPECT_NE(b.env("press 43 60 0").rfind("error", 0), std::string::npos);
  b.advance_to(160'000);
  EXPECT_EQ(b.env("press 43 60 0"), "ok");
  EXPECT_NE(b.env("press 43 60 0").rfind("error", 0), std::string::npos);
}

TEST(Hc08SimBoard, TheRunIsDeterministic) {
  const h::Scenario s = h::parse_file(std::string(AP_HC08_SCENARIOS) + "/mode_a_ramp_stop.scn");
  h::Board a(h::BoardOptions{}), b(h::BoardOptions{});
  drive(a, s);
  drive(b, s);
  const std::string pa = testing::TempDir() + "/hc08_det_a.csv", pb = testing::TempDir() + "/hc08_det_b.csv";
  h::write_trace_csv(a.rows(), pa);
  h::write_trace_csv(b.rows(), pb);
  EXPECT_EQ(slurp(pa), slurp(pb));
  EXPECT_EQ(a.rows().size(), b.rows().size());
}

TEST(Hc08SimBoard, TheVcdPhaseLinesAreThePortOfTheRun) {
  const h::Scenario s = h::parse_file(std::string(AP_HC08_SCENARIOS) + "/mode_b_half_90.scn");
  h::Board b(h::BoardOptions{});
  drive(b, s);
  const std::string path = testing::TempDir() + "/hc08_phases.vcd";
  h::write_vcd(b.rows(), path);
  namespace wf = ap::model::waveform;
  const wf::VcdDoc vcd = wf::parse_vcd(slurp(path));
  EXPECT_EQ(vcd.timescale, "1ns");
  std::set<std::uint64_t> row_times;
  for (const h::Row& r : b.rows()) row_times.insert(h::ns_of(r.t));
  for (unsigned k = 0; k < 4; ++k) {
    const wf::VcdDoc::Var* v = vcd.find("hc08", "phase" + std::to_string(k + 1));
    ASSERT_NE(v, nullptr) << "phase" << k + 1;
    const auto tr = vcd.trace(v->id);
    ASSERT_FALSE(tr.empty());
    // The line's level at every row is PTA(3 + k) of that row.
    for (const h::Row& r : b.rows()) {
      const std::uint64_t t = h::ns_of(r.t);
      char level = tr.front().second;
      for (const auto& [at, l] : tr) {
        if (at <= t) level = l;
      }
      EXPECT_EQ(level, ((r.port >> (3U + k)) & 1U) != 0 ? '1' : '0') << "phase" << k + 1 << " at " << t << " ns";
    }
    // And it changes only when the run changed the port.
    for (std::size_t i = 1; i < tr.size(); ++i) EXPECT_EQ(row_times.count(tr[i].first), 1U) << tr[i].first;
  }
  // 20 half steps: each changes exactly one line (half step alternates one and two coils).
  std::size_t edges = 0;
  for (unsigned k = 0; k < 4; ++k) edges += vcd.trace(vcd.find("hc08", "phase" + std::to_string(k + 1))->id).size() - 1;
  EXPECT_EQ(edges, 20U);
}

TEST(Hc08SimBoard, OutputsAgreeWithTheRun) {
  const h::Scenario s = h::parse(
      "scenario outputs_check\nduration 1 s\nat 100 ms press minus\nat 300 ms press set bounce\nexpect end steps == 10\n");
  const h::RunResult r = run(s);
  ASSERT_TRUE(r.pass) << h::format_report(s, r);
  const std::string csv = slurp(r.out_dir + "/trace.csv");
  EXPECT_EQ(csv.rfind("t_us,event,key,port,pattern,dir,period_ticks,angle_tenths,position_half,steps,running,state,", 0), 0U);
  EXPECT_EQ(count_of(csv, ",step,"), 10U);
  EXPECT_EQ(count_of(csv, ",key,0x"), 2U);
  // The SET with bounce counts at the 24th scan (stable from the 5th): the move starts at
  // 324 ms, the first step 25 ms later; the last one leaves 1100 on the coils, port 0x60.
  EXPECT_NE(csv.find("\n349000.000,step,0x2D,0x30,0110,1,61440,90,2,1,1,S_DEF,1,90,1,0,0\n"), std::string::npos);
  EXPECT_NE(csv.find("\n574000.000,step,0x00,0x60,1100,1,61440,900,20,10,0,S_DEF,1,900,1,0,0\n"), std::string::npos);
  namespace wf = ap::model::waveform;
  const wf::VcdDoc vcd = wf::parse_vcd(slurp(r.out_dir + "/waveforms.vcd"));
  const wf::VcdDoc::Var* key = vcd.find("hc08", "key");
  ASSERT_NE(key, nullptr);
  EXPECT_EQ(key->width, 8U);
  const std::string svg = slurp(r.out_dir + "/plots.svg");
  EXPECT_NO_THROW(wf::parse_xml(svg));
  EXPECT_EQ(count_of(svg, "<polyline class=\"series\""), 2U);
  EXPECT_NE(slurp(r.out_dir + "/report.txt").find("hc08 scenario outputs_check: PASS"), std::string::npos);
}
