// The unit3 profile end to end (docs/unit3-sim.md), suites Unit3Sim*:
//   Unit3SimScenario/Bundled.Passes/NAME  every scenarios/unit3/*.scn passes over the DDS bus
//   Unit3SimVerdict.*                     a wrong expectation of each kind fails the run
//   Unit3SimParser.*                      the language's errors name file:line
//   Unit3SimSafety.*                      each safety property catches a planted violation in
//                                         a hand-made trace, and the real unit's trace is clean
//   Unit3SimBoard.*                       the UART line rate both ways, the outputs
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "profile_sim_support.hpp"
#include "sim/unit3/unit3.hpp"

namespace fs = std::filesystem;
namespace u3 = ap::sim::unit3;
using ap::unit3_board::Source;

namespace {

using ap::sim::test::count_of;
using ap::sim::test::says;
using ap::sim::test::slurp;

std::vector<std::string> bundled() { return ap::sim::test::bundled(AP_UNIT3_SCENARIOS); }

std::string out_root() { return std::string(AP_BINARY_DIR) + "/sim-out/unit3"; }

u3::RunResult run(const u3::Scenario& s, const std::string& root = out_root()) {
  u3::RunOptions o;
  o.out_root = root;
  return u3::run_scenario(s, o);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
class Bundled : public ::testing::TestWithParam<std::string> {};

TEST_P(Bundled, Passes) {
  const u3::Scenario s = u3::parse_file(std::string(AP_UNIT3_SCENARIOS) + "/" + GetParam() + ".scn");
  const u3::RunResult r = run(s);
  std::cout << u3::format_report(s, r);
  EXPECT_TRUE(r.pass);
  EXPECT_TRUE(r.failures.empty());
  EXPECT_EQ(r.passed.size(), s.expectations.size());
  EXPECT_EQ(r.vtime_us, s.duration_us);
  // Every tick of the run went through the safety checker.
  EXPECT_EQ(r.ticks, static_cast<std::uint64_t>(s.duration_us / 1000));
  for (const char* f : {"trace.csv", "waveforms.vcd", "plots.svg", "report.txt"}) {
    EXPECT_TRUE(fs::is_regular_file(r.out_dir + "/" + f)) << f;
  }
}

INSTANTIATE_TEST_SUITE_P(Unit3SimScenario, Bundled, ::testing::ValuesIn(bundled()), ap::sim::test::test_name);

TEST(Unit3SimScenario, AtLeastEightAreBundled) { EXPECT_GE(bundled().size(), 8U); }

// ---------------------------------------------------------------------------------------------
// The expectations can fail: the thesis's example with each kind of expectation made wrong.
TEST(Unit3SimVerdict, EveryKindOfExpectationCanFail) {
  const std::string head =
      "scenario verdict\nduration 2 s\nat 10 ms send \"M000;\"\nat 50 ms send \"D+++;Y000000000016000;\"\n";
  const std::vector<std::string> wrong = {
      "expect report y == 15968",                    // the last report is +16000
      "expect by 0.5 s report y == 16000",           // the move has not ended by 0.5 s
      "expect report x == 0",                        // X never reported
      "expect reply \"E20;\"",                       // never sent
      "expect no reply \"M000;\"",                   // sent
      "expect replies \"T444;\" == 2",               // sent once
      "expect settings \"M000;T445;\"",
      "expect by 10 ms settings \"M000;T444;\"",     // not yet on the line
      "expect end pulses y == 499",
      "expect end counter y != 16000",
      "expect at 0.5 s running y == 0",
      "expect at 0.5 s dir y == -",
      "expect between 0.3 s and end pulses y == 500",  // Y pulsed before 0.3 s
  };
  for (std::size_t i = 0; i < wrong.size(); ++i) {
    const u3::Scenario s = u3::parse(head + wrong[i] + "\n", "verdict.scn");
    const u3::RunResult r = run(s, "");
    EXPECT_FALSE(r.pass) << wrong[i];
    ASSERT_EQ(r.failures.size(), 1U) << wrong[i];
    EXPECT_NE(r.failures[0].find("line 5"), std::string::npos) << r.failures[0];
  }
  // The same lines made right pass (the failures above are the expectations', not the run's).
  const u3::Scenario ok = u3::parse(head +
                                        "expect report y == 16000\nexpect end pulses y == 500\n"
                                        "expect settings \"M000;T444;\"\nexpect at 0.5 s running y == 1\n"
                                        "expect no errors\nexpect report y == counter\n",
                                    "verdict.scn");
  const u3::RunResult r = run(ok, "");
  EXPECT_TRUE(r.pass) << u3::format_report(ok, r);
}

TEST(Unit3SimVerdict, AnErrorReplyFailsNoErrors) {
  const u3::Scenario s = u3::parse("scenario e\nduration 1 s\nat 10 ms send \"Q;\"\nexpect no errors\nexpect reply \"E01;\"\n");
  const u3::RunResult r = run(s, "");
  EXPECT_FALSE(r.pass);
  ASSERT_EQ(r.failures.size(), 1U);
  EXPECT_NE(r.failures[0].find("E01;"), std::string::npos) << r.failures[0];
}

TEST(Unit3SimVerdict, AnAdcGlitchIsFullScale) {
  // A reading past 10 bits is taken as 1023 (docs/unit3.md "The joystick"): index 31, reached
  // after 31 ramp intervals of 10 ms.
  const u3::Scenario s = u3::parse("scenario g\nduration 1 s\nat 0 ms joystick x 65535\nexpect at 0.5 s entry x == 31\n");
  const u3::RunResult r = run(s, "");
  EXPECT_TRUE(r.pass) << u3::format_report(s, r);
}

// ---------------------------------------------------------------------------------------------
namespace {

void parse(const std::string& text, const std::string& file) { (void)u3::parse(text, file); }

}  // namespace

TEST(Unit3SimParser, ReadsEveryStatement) {
  const u3::Scenario s = u3::parse(
      "# comment\n"
      "scenario all_of_it   # trailing comment\n"
      "title \"T \\\"q\\\"\"\n"
      "duration 2.5 s\n"
      "eeprom blank\n"
      "at 1 s press right x3\n"
      "at 10 ms send \"D+-+;\\r\\n\\x41\" lose 1\n"
      "at 0.5 s joystick z 0\n"
      "at 600ms endstop x min on\n"
      "at 700 ms power-cycle\n"
      "expect by 2 s report y >= -5\n"
      "expect report z == counter\n"
      "expect replies \"E20;\" <= 3\n"
      "expect reply \"E21;\"\n"
      "expect no reply \"E22;\"\n"
      "expect no errors\n"
      "expect settings \"M000;T444;\"\n"
      "expect at 1 s dir x == -\n"
      "expect end pulses y != 4\n"
      "expect at end entry z < 31\n"
      "expect between 0.5 s and end counter x > 7\n",
      "all.scn");
  EXPECT_EQ(s.name, "all_of_it");
  EXPECT_EQ(s.title, "T \"q\"");
  EXPECT_EQ(s.duration_us, 2'500'000);
  EXPECT_EQ(s.eeprom, u3::Eeprom::Blank);
  ASSERT_EQ(s.actions.size(), 5U);
  // In time order: send 10 ms, joystick 0.5 s, endstop 0.6 s, power-cycle 0.7 s, press 1 s.
  EXPECT_EQ(s.actions[0].kind, u3::ActionKind::Send);
  EXPECT_EQ(s.actions[0].bytes, "D-+;\r\nA");  // byte 1 ('+') lost
  EXPECT_EQ(s.actions[1].adc, 0);
  EXPECT_EQ(s.actions[1].axis, 2);
  EXPECT_EQ(s.actions[2].t_us, 600'000);
  EXPECT_FALSE(s.actions[2].max_end);
  EXPECT_TRUE(s.actions[2].on);
  EXPECT_EQ(s.actions[3].kind, u3::ActionKind::PowerCycle);
  EXPECT_EQ(s.actions[4].times, 3U);
  ASSERT_EQ(s.expectations.size(), 11U);
  EXPECT_EQ(s.expectations[0].value, -5);
  EXPECT_EQ(s.expectations[0].op, u3::Op::Ge);
  EXPECT_TRUE(s.expectations[1].value_is_counter);
  EXPECT_EQ(s.expectations[1].t_us, 2'500'000);  // no `by`: the end
  EXPECT_EQ(s.expectations[3].op, u3::Op::Ge);
  EXPECT_EQ(s.expectations[4].value, 0);
  EXPECT_EQ(s.expectations[7].value, -1);
  EXPECT_EQ(s.expectations[9].t_us, 2'500'000);
  EXPECT_EQ(s.expectations[10].kind, u3::ExpectKind::Between);
  EXPECT_EQ(s.expectations[10].t0_us, 500'000);
}

TEST(Unit3SimParser, ErrorsNameTheFileAndLine) {
  const std::string ok = "scenario s\nduration 1 s\n";  // lines 1-2
  ap::sim::test::expect_errors(parse, {
      {ok + "at 10 ms send \"abc\n", 3, "unterminated string"},
      {ok + "at 10 parsecs send \"a\"\n", 3, "bad time"},
      {ok + "at 10 ms sned \"a\"\n", 3, "unknown action"},
      {ok + "\n\nat 10 ms joystick w 5\n", 5, "unknown axis"},
      {ok + "at 10 ms joystick x 70000\n", 3, "outside 0..65535"},
      {ok + "at 10 ms endstop x middle on\n", 3, "min or max"},
      {ok + "at 10 ms press jump\n", 3, "unknown button"},
      {ok + "at 10 ms send \"ab\" lose 2\n", 3, "bytes 0..1"},
      {ok + "at 2 s power-cycle\n", 3, "after the end"},
      {ok + "expect by 3 s report x == 1\n", 3, "after the end"},
      {ok + "expect report x =< 1\n", 3, "unknown comparison"},
      {ok + "expect at 1 s speed x == 1\n", 3, "unknown quantity"},
      {ok + "expect between 0.5 s and 0.2 s pulses x == 1\n", 3, "T1 < T2"},
      {ok + "expect settings \"M000;\"\n", 3, "M<d><d><d>;T<d><d><d>;"},
      {ok + "expect at 0.5 s pulses x == 1 extra\n", 3, "unexpected 'extra'"},
      {ok + "eeprom dusty\n", 3, "default or blank"},
      {ok + "duration 2 s\n", 3, "second 'duration'"},
      {"duration 1 s\nscenario bad/name\n", 2, "letters, digits"},
      {"scenario s\n", 1, "no 'duration'"},
      {ok + "launch\n", 3, "unknown statement"},
      {ok + "at 10 ms send \"\\q\"\n", 3, "unknown escape"},
  });
}

// Times in exact microseconds: properties/sim/scenario_text_test.cpp. Here, that the unit3
// language reads them in its dialect (up to 10^12 us of virtual time).
TEST(Unit3SimParser, TimesInTheUnit3Dialect) {
  std::int64_t us = 0;
  EXPECT_TRUE(u3::parse_time("0.52", "ms", us));
  EXPECT_EQ(us, 520);
  EXPECT_FALSE(u3::parse_time("0.5", "us", us));  // finer than 1 us
  EXPECT_TRUE(u3::parse_time("1000000", "s", us));
  EXPECT_EQ(us, 1'000'000'000'000LL);
  EXPECT_FALSE(u3::parse_time("1000000.000001", "s", us));
}

// ---------------------------------------------------------------------------------------------
// Hand-made traces: one axis (Y) doing something, X and Z at rest.
namespace {

struct Trace {
  std::vector<u3::TickSample> ticks;
  u3::TickSample& at(std::uint64_t t) {
    while (ticks.size() < t) {
      u3::TickSample s;
      s.t_ms = ticks.size() + 1;
      if (!ticks.empty()) {
        s.endstops = ticks.back().endstops;
        for (std::size_t a = 0; a < u3::kAxes; ++a) {
          s.axis[a] = ticks.back().axis[a];
          s.axis[a].pulses = 0;
          s.axis[a].pulse_at = 0;
        }
      }
      ticks.push_back(s);
    }
    return ticks[t - 1];
  }
  // Y runs over ticks [from, to] for `src` at `entry` with `dir`, pulsing every `period` ticks
  // (at the end of the tick) starting `period` ticks after the start.
  void run(std::uint64_t from, std::uint64_t to, std::uint8_t entry, std::int8_t dir, std::uint64_t period,
           Source src = Source::Joystick) {
    for (std::uint64_t t = from; t <= to; ++t) {
      u3::AxisSample& y = at(t).axis[1];
      y.source = src;
      y.running = true;
      y.entry = entry;
      y.dir = dir;
      if ((t - from + 1) % period == 0) {
        y.pulses = 1;
        y.pulse_at = 250;
      }
    }
  }
  void idle(std::uint64_t from, std::uint64_t to) {
    for (std::uint64_t t = from; t <= to; ++t) {
      u3::AxisSample& y = at(t).axis[1];
      y.source = Source::Idle;
      y.running = false;
      y.entry = 0;
      y.remaining = 0;
    }
  }
  std::vector<std::string> check() const {
    u3::SafetyChecker c;
    for (const u3::TickSample& s : ticks) c.check(s);
    return c.violations();
  }
};

// A ramp the checker accepts: start at 0, one entry per 10 ms up to `top`, down again, stop.
// Entry 0 pulses every 40 ticks, higher entries every 4 (well inside every period bound).
Trace clean_ramp(std::uint8_t top, std::int8_t dir) {
  Trace tr;
  tr.idle(1, 1);
  std::uint64_t t = 2;
  for (int e = 0; e <= top; ++e, t += 10) tr.run(t, t + 9, static_cast<std::uint8_t>(e), dir, e == 0 ? 40 : 4);
  for (int e = top - 1; e >= 0; --e, t += 10) tr.run(t, t + 9, static_cast<std::uint8_t>(e), dir, e == 0 ? 40 : 4);
  tr.idle(t, t + 5);
  return tr;
}

}  // namespace

TEST(Unit3SimSafety, AControlledRampAndReversalIsClean) {
  Trace tr = clean_ramp(5, +1);
  const std::uint64_t t = tr.ticks.size() + 1;
  // The reversal from rest after a stop from entry 0.
  tr.run(t, t + 9, 0, -1, 40);
  tr.idle(t + 10, t + 12);
  EXPECT_TRUE(tr.check().empty()) << tr.check().front();
}

TEST(Unit3SimSafety, ReverseCatchesADirectionChangeAboveEntryZero) {
  // Running upwards at entry 3, stopped (not by an endstop), restarted downwards.
  Trace tr;
  tr.idle(1, 1);
  for (std::uint64_t t = 2, e = 0; e <= 3; ++e, t += 10) tr.run(t, t + 9, static_cast<std::uint8_t>(e), +1, 4);
  tr.idle(42, 42);
  tr.run(43, 50, 0, -1, 4);
  EXPECT_TRUE(says(tr.check(), "DIR reversed after a stop from ramp entry 3")) << ::testing::PrintToString(tr.check());
  // And while running: DIR flips at entry 2 without a stop.
  Trace tr2;
  tr2.idle(1, 1);
  for (std::uint64_t t = 2, e = 0; e <= 2; ++e, t += 10) tr2.run(t, t + 9, static_cast<std::uint8_t>(e), +1, 4);
  tr2.run(32, 40, 2, -1, 4);
  EXPECT_TRUE(says(tr2.check(), "DIR reversed while running at ramp entry 2")) << ::testing::PrintToString(tr2.check());
  // An endstop stop from speed may be followed by a move away (the thesis's interrupt stop).
  Trace tr3;
  tr3.idle(1, 1);
  for (std::uint64_t t = 2, e = 0; e <= 3; ++e, t += 10) tr3.run(t, t + 9, static_cast<std::uint8_t>(e), +1, 4);
  tr3.at(42).endstops = ap::unit3_board::endstop_bit(1, true);
  tr3.idle(42, 45);
  tr3.run(46, 60, 0, -1, 10);
  EXPECT_TRUE(tr3.check().empty()) << ::testing::PrintToString(tr3.check());
}

TEST(Unit3SimSafety, RampCatchesAJumpAFastChangeAndAFlyingStart) {
  Trace jump;
  jump.idle(1, 1);
  jump.run(2, 11, 0, +1, 4);
  jump.run(12, 21, 2, +1, 4);  // 0 -> 2
  EXPECT_TRUE(says(jump.check(), "ramp entry jumped from 0 to 2")) << ::testing::PrintToString(jump.check());
  Trace fast;
  fast.idle(1, 1);
  fast.run(2, 11, 0, +1, 4);
  fast.run(12, 16, 1, +1, 4);
  fast.run(17, 30, 2, +1, 4);  // 5 ms after the last change
  EXPECT_TRUE(says(fast.check(), "changed 5 ms after the last change")) << ::testing::PrintToString(fast.check());
  Trace flying;
  flying.idle(1, 1);
  flying.run(2, 20, 4, +1, 4);
  EXPECT_TRUE(says(flying.check(), "started at ramp entry 4")) << ::testing::PrintToString(flying.check());
}

TEST(Unit3SimSafety, StopCatchesAPcMoveEndingAboveEntryZero) {
  // A PC move whose last pulse comes 20 ticks (5000 clocks) after the one before: the rate of
  // entry 1, not 0.
  Trace tr;
  tr.idle(1, 1);
  tr.run(2, 41, 0, +1, 40, Source::Pc);  // pulse at tick 41 (10000 clocks after the start)
  tr.run(42, 60, 0, +1, 40, Source::Pc);  // no pulse in 42..60
  tr.idle(61, 61);                         // the stop tick, with the last pulse
  tr.at(61).axis[1].pulses = 1;
  tr.at(61).axis[1].pulse_at = 250;
  const auto v = tr.check();
  EXPECT_TRUE(says(v, "the PC move's last pulse came 5000 timer clocks after the one before")) << ::testing::PrintToString(v);
  // The same move ending one entry-0 period after its previous pulse is clean.
  Trace ok;
  ok.idle(1, 1);
  ok.run(2, 80, 0, +1, 40, Source::Pc);  // a pulse at tick 41; the last one in the stop tick, 81
  ok.idle(81, 81);
  ok.at(81).axis[1].pulses = 1;
  ok.at(81).axis[1].pulse_at = 250;
  EXPECT_TRUE(ok.check().empty()) << ::testing::PrintToString(ok.check());
}

TEST(Unit3SimSafety, EndstopCatchesAPulseTowardsAClosedSwitch) {
  Trace tr;
  tr.idle(1, 1);
  tr.run(2, 60, 0, -1, 40);
  tr.at(41).endstops = ap::unit3_board::endstop_bit(1, false);  // Y min, ahead of dir -1
  EXPECT_TRUE(says(tr.check(), "STEP pulse towards the closed min endstop")) << ::testing::PrintToString(tr.check());
  // The other end closed is no violation.
  Trace other;
  other.idle(1, 1);
  other.run(2, 60, 0, -1, 40);
  other.at(41).endstops = ap::unit3_board::endstop_bit(1, true);
  EXPECT_TRUE(other.check().empty()) << ::testing::PrintToString(other.check());
}

TEST(Unit3SimSafety, GapCatchesARunningAxisThatStopsPulsing) {
  Trace tr;
  tr.idle(1, 1);
  tr.run(2, 100, 0, +1, 45);  // 45 ticks = 11250 clocks between pulses
  EXPECT_TRUE(says(tr.check(), "timer clocks (at most 10000)")) << ::testing::PrintToString(tr.check());
}

TEST(Unit3SimSafety, TheRealUnitsTraceIsCleanAndAPlantedFaultInItIsNot) {
  // The unit itself, driven directly: a Y move of 200 full steps, then one back.
  std::array<std::uint8_t, ap::unit3_settings::kImageSize> ee{};
  ap::unit3_settings::store(ap::unit3_settings::kDefaults, ee);
  ap::unit3_board::Unit u(ee);
  std::vector<u3::TickSample> samples;
  const auto send = [&](const std::string& s) {
    for (const char c : s) u.receive(static_cast<std::uint8_t>(c));
  };
  send("D+++;Y000000000006400;");
  for (std::uint64_t t = 1; t <= 2000; ++t) {
    if (t == 1000) send("D---;Y000000000006400;");
    u.tick({});
    samples.push_back(u3::sample_of(u, t, 0));
  }
  u3::SafetyChecker clean;
  for (const auto& s : samples) clean.check(s);
  EXPECT_TRUE(clean.violations().empty()) << clean.violations().front();
  EXPECT_EQ(u.axis(1).counter, 0);
  // Planted: the first move's stop tick, with its last pulse, 8 ms earlier (as a unit that
  // stops while still above entry 0 would put it).
  auto planted = samples;
  std::size_t last = 0;
  for (std::size_t i = 0; i < 999; ++i) {
    if (samples[i].axis[1].pulses > 0) last = i;
  }
  ASSERT_GT(last, 10U);
  ASSERT_FALSE(samples[last].axis[1].running);  // the stop tick
  planted[last - 8].axis[1] = samples[last].axis[1];
  for (std::size_t i = last - 7; i <= last; ++i) {
    planted[i].axis[1] = samples[last].axis[1];
    planted[i].axis[1].pulses = 0;
    planted[i].axis[1].pulse_at = 0;
  }
  u3::SafetyChecker c;
  for (const auto& s : planted) c.check(s);
  EXPECT_TRUE(says(c.violations(), "the PC move's last pulse")) << ::testing::PrintToString(c.violations());
}

// ---------------------------------------------------------------------------------------------
TEST(Unit3SimBoard, BytesCrossTheLineAt1920PerSecond) {
  u3::BoardOptions o;
  u3::Board b(o);
  // 22 bytes written at t = 0: the move's `;` ends at 22 x 520.83 us = 11.46 ms, so the move
  // starts in the tick ending at 12 ms, not before.
  const std::string cmd = "D+++;Y000000000000032;";
  b.rx(std::vector<std::uint8_t>(cmd.begin(), cmd.end()), 0);
  b.advance_to(11'000);
  EXPECT_FALSE(b.unit().out(1).running);
  b.advance_to(12'000);
  EXPECT_TRUE(b.unit().out(1).running);
  // G; at 100 ms: executed in the tick ending at 102 ms (1.04 ms on the line); its 10 reply bytes
  // go out back to back from 102 ms, the last ending at 102 + 5.21 ms.
  // The one-pulse move ends and reports; nothing else is on the line by 100 ms.
  b.advance_to(100'000);
  const auto report = b.take_tx(1000);
  EXPECT_EQ(std::string(report.begin(), report.end()), "Y+000000000000000032;");
  const std::string g = "G;";
  b.rx(std::vector<std::uint8_t>(g.begin(), g.end()), 100'000);
  b.advance_to(104'000);
  const auto first = b.take_tx(1000);
  EXPECT_EQ(first.size(), 3U);  // ends at 102.52, 103.04, 103.56 ms
  b.advance_to(108'000);
  const auto rest = b.take_tx(1000);
  std::string all(first.begin(), first.end());
  all.append(rest.begin(), rest.end());
  EXPECT_EQ(all, "M000;T444;");
}

TEST(Unit3SimBoard, OutputsAgreeWithTheRun) {
  const u3::Scenario s = u3::parse(
      "scenario outputs_check\nduration 1500 ms\nat 10 ms send \"D+-+;Y000000000003200;\"\nat 20 ms send \"M011;\"\n"
      "expect end pulses y == 100\n");
  const u3::RunResult r = run(s);
  ASSERT_TRUE(r.pass) << u3::format_report(s, r);
  const std::string csv = slurp(r.out_dir + "/trace.csv");
  EXPECT_EQ(csv.rfind("t_ms,axis,source,entry,dir,mode,counter,remaining,pulses,running", 0), 0U);
  EXPECT_EQ(count_of(csv, "\n"), 1U + 3U * 1500U);
  // M011; came while Y moved: Y's MODE pins change only once it is at rest (core/unit3/board);
  // Z, at rest, takes it at once.
  EXPECT_NE(csv.find("\n1500,y,idle,0,-1,1,-3200,0,0,0,"), std::string::npos);
  EXPECT_NE(csv.find("\n1500,z,idle,0,1,1,"), std::string::npos);
  std::istringstream rows(csv);
  std::size_t y_running = 0;
  for (std::string row; std::getline(rows, row);) {
    if (row.find(",y,pc,") == std::string::npos) continue;
    ++y_running;
    EXPECT_NE(row.find(",-1,0,"), std::string::npos) << row;  // dir -1, mode 0
  }
  EXPECT_GT(y_running, 100U);
  namespace wf = ap::model::waveform;
  const wf::VcdDoc vcd = wf::parse_vcd(slurp(r.out_dir + "/waveforms.vcd"));
  EXPECT_EQ(vcd.timescale, "1us");
  const auto edges = [&](const char* name, char level) {
    const wf::VcdDoc::Var* v = vcd.find("unit3.Y", name);
    if (v == nullptr) {
      ADD_FAILURE() << "no unit3.Y." << name;
      return std::size_t{0};
    }
    const auto tr = vcd.trace(v->id);
    std::size_t n = 0;
    for (std::size_t i = 1; i < tr.size(); ++i) n += tr[i].second == level ? 1U : 0U;
    return n;
  };
  // Y's STEP: 100 pulses, each 2 us high.
  EXPECT_EQ(edges("step", '1'), 100U);
  EXPECT_EQ(edges("step", '0'), 100U);
  // Y's DIR goes low once, when the move starts; its MODE0 rises once, after it.
  EXPECT_EQ(edges("dir", '0'), 1U);
  EXPECT_EQ(edges("mode0", '1'), 1U);
  const std::string svg = slurp(r.out_dir + "/plots.svg");
  EXPECT_NO_THROW(wf::parse_xml(svg));
  EXPECT_EQ(count_of(svg, "<polyline class=\"series\""), 6U);  // two panels, three axes
  EXPECT_NE(slurp(r.out_dir + "/report.txt").find("unit3 scenario outputs_check: PASS"), std::string::npos);
}
