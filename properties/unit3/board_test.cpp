// The unit's firmware (core/unit3/board) against seed 001 and docs/unit3.md "The board".
// Expected values are worked out by hand from the thesis's numbers and the documented rules.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/unit3/board/unit.hpp"
#include "sim/unit3/replies.hpp"

namespace {

namespace u = ap::unit3_board;
using Button = ap::unit3_menu::Button;

struct Rig {
  std::array<std::uint8_t, 8> eeprom;
  u::Unit unit;
  u::Inputs in{};
  std::string rx;  // everything the PC received
  std::array<std::uint64_t, 3> pulses{};
  std::array<int, 3> max_entry{};

  Rig() : eeprom(blank()), unit(eeprom) {}
  static std::array<std::uint8_t, 8> blank() {
    std::array<std::uint8_t, 8> e{};
    e.fill(0xFF);
    return e;
  }
  void send(const std::string& s) {
    for (const char c : s) unit.receive(static_cast<std::uint8_t>(c));
    drain();
  }
  void drain() { rx += ap::sim::unit3::take_all(unit); }
  void run(int ms) {
    for (int i = 0; i < ms; ++i) {
      unit.tick(in);
      for (std::size_t a = 0; a < 3; ++a) {
        pulses[a] += unit.out(a).pulses;
        if (unit.axis(a).entry > max_entry[a]) max_entry[a] = unit.axis(a).entry;
      }
      drain();
    }
  }
  bool running() const {
    return unit.axis(0).source != u::Source::Idle || unit.axis(1).source != u::Source::Idle ||
           unit.axis(2).source != u::Source::Idle;
  }
  void settle(int max_ms = 200'000) {
    for (int i = 0; i < max_ms && running(); ++i) run(1);
  }
  // The replies, split after each ';'.
  std::vector<std::string> replies() const { return ap::sim::unit3::split_replies(rx); }
  std::string last_report(char axis) const {
    std::string last;
    for (const auto& r : replies()) {
      if (r.size() == 21 && r[0] == axis) last = r;
    }
    return last;
  }
};

TEST(Unit3Board, ThesisExampleFullStep) {
  // Y000000000016000; in full step = 500 full steps = 16000 counts [T §2.3].
  Rig r;
  r.send("M000;D+++;Y000000000016000;");
  r.settle();
  EXPECT_EQ(r.pulses[1], 500U);
  EXPECT_EQ(r.unit.axis(1).counter, 16000);
  EXPECT_EQ(r.last_report('Y'), "Y+000000000000016000;");
  EXPECT_EQ(r.pulses[0] + r.pulses[2], 0U);
}

TEST(Unit3Board, ThesisExampleThirtySecondStep) {
  // Y000000000000500; at 1/32 = 500 microsteps = 500 counts [T §2.3]; MODE pins 101 [T Tab. 7].
  Rig r;
  r.send("M555;D+-+;Y000000000000500;");
  r.run(1);
  EXPECT_TRUE(r.unit.out(1).mode.m2 && !r.unit.out(1).mode.m1 && r.unit.out(1).mode.m0);
  EXPECT_EQ(r.unit.out(1).dir, -1);
  r.settle();
  EXPECT_EQ(r.pulses[1], 500U);
  EXPECT_EQ(r.last_report('Y'), "Y-000000000000000500;");
}

TEST(Unit3Board, SettingsRepliesAndEepromSurvivePowerCycle) {
  Rig r;
  EXPECT_EQ(r.unit.loaded(), ap::unit3_settings::Load::Blank);
  r.send("M123;T056;");
  const auto rep = r.replies();
  ASSERT_EQ(rep.size(), 4U);
  EXPECT_EQ(rep[0], "M123;");
  EXPECT_EQ(rep[1], "T444;");  // the defaults' threads: M6 [D]
  EXPECT_EQ(rep[3], "T056;");
  u::Unit again(r.eeprom);
  EXPECT_EQ(again.loaded(), ap::unit3_settings::Load::Ok);
  EXPECT_EQ(again.settings().mode[2], 3);
  EXPECT_EQ(again.settings().thread[1], 5);
  EXPECT_EQ(again.axis(0).counter, 0);
}

TEST(Unit3Board, RefusedLinesAnswerWithTheirCodeAndRunNothing) {
  Rig r;
  r.send("Y00000000001600;");   // a digit lost: 16 bytes -> bad_length (02)
  r.send("Q;");                 // unknown (01)
  r.send("M606;");              // mode 6 (05)
  r.send("X00000000001600a;");  // bad digit (03)
  r.run(50);
  EXPECT_EQ(r.rx, "E02;E01;E05;E03;");
  EXPECT_EQ(r.pulses[0] + r.pulses[1], 0U);
}

TEST(Unit3Board, MoveNotAWholeNumberOfPulsesIsRefused) {
  Rig r;  // full step after a blank EEPROM: 32 counts per pulse
  r.send("X000000000000500;");
  r.run(100);
  EXPECT_EQ(r.rx, "E21;");
  EXPECT_EQ(r.pulses[0], 0U);
}

TEST(Unit3Board, MoveDuringMotionIsRefusedAndTheFirstCompletes) {
  Rig r;
  r.send("X000000000003200;");  // 100 pulses
  r.run(30);
  r.send("X000000000000032;");
  r.settle();
  EXPECT_NE(r.rx.find("E20;"), std::string::npos);
  EXPECT_EQ(r.pulses[0], 100U);
  EXPECT_EQ(r.unit.axis(0).counter, 3200);
}

TEST(Unit3Board, ClearZeroesTheCountersWithoutStoppingTheMove) {
  Rig r;
  r.send("X000000000003200;");
  r.run(200);
  const std::uint64_t before = r.pulses[0];
  ASSERT_GT(before, 0U);
  ASSERT_LT(before, 100U);
  r.send("C;");
  EXPECT_TRUE(r.running());
  r.settle();
  EXPECT_EQ(r.pulses[0], 100U);
  EXPECT_EQ(r.unit.axis(0).counter, static_cast<std::int64_t>(32 * (100 - before)));
}

TEST(Unit3Board, StepModeReachesARunningAxisOnlyWhenItStops) {
  Rig r;
  r.send("X000000000000320;");  // 10 pulses in full step
  r.run(50);
  ASSERT_TRUE(r.running());
  r.send("M500;");
  r.run(1);
  EXPECT_FALSE(r.unit.out(0).mode.m2);  // still full step on the pins
  r.settle();
  EXPECT_EQ(r.unit.axis(0).counter, 320);
  r.run(1);
  EXPECT_TRUE(r.unit.out(0).mode.m2 && r.unit.out(0).mode.m0);
}

TEST(Unit3Board, EndstopCutsAMoveAndAllowsMotionAway) {
  Rig r;
  r.send("D+++;X000000000032000;");  // 1000 pulses towards X max
  r.run(300);
  r.in.endstops = u::endstop_bit(0, true);
  r.run(1);
  EXPECT_FALSE(r.running());
  const std::int64_t stopped = r.unit.axis(0).counter;
  EXPECT_GT(stopped, 0);
  EXPECT_LT(stopped, 32000);
  const auto rep = r.replies();
  ASSERT_GE(rep.size(), 2U);
  EXPECT_EQ(rep[rep.size() - 2], "E23;");
  EXPECT_EQ(rep.back(), r.last_report('X'));
  const std::uint64_t at_stop = r.pulses[0];
  r.run(100);
  EXPECT_EQ(r.pulses[0], at_stop);
  r.rx.clear();
  r.send("X000000000000032;");  // towards the closed end: refused
  EXPECT_EQ(r.rx, "E23;");
  r.send("D-++;X000000000000320;");  // away from it: runs
  r.settle();
  EXPECT_EQ(r.unit.axis(0).counter, stopped - 320);
}

TEST(Unit3Board, StickRampsUpOneEntryPer10msAndReversesFromEntryZero) {
  Rig r;
  r.in.adc[2] = 1023;  // full up: index 31
  r.run(400);
  EXPECT_EQ(r.unit.axis(2).entry, 31);
  EXPECT_EQ(r.unit.axis(2).source, u::Source::Joystick);
  r.in.adc[2] = 0;  // full down
  int last_dir = r.unit.out(2).dir;
  int prev_entry = r.unit.axis(2).entry;
  bool reversed = false;
  for (int i = 0; i < 1000; ++i) {
    r.run(1);
    if (r.unit.out(2).dir != last_dir) {
      EXPECT_EQ(prev_entry, 0) << "reversed at entry " << prev_entry;
      reversed = true;
    }
    last_dir = r.unit.out(2).dir;
    prev_entry = r.unit.axis(2).entry;
  }
  EXPECT_TRUE(reversed);
  EXPECT_EQ(r.unit.out(2).dir, -1);
}

TEST(Unit3Board, StickIgnoredWhileAPcMoveRunsTheAxis) {
  Rig r;
  r.send("D---;X000000000000640;");  // 20 pulses down
  r.in.adc[0] = 1023;
  r.run(10);
  EXPECT_EQ(r.unit.axis(0).source, u::Source::Pc);
  r.in.adc[0] = 512;
  r.settle();
  EXPECT_EQ(r.unit.axis(0).counter, -640);
}

// The endstop pins are active low (docs/unit3.md "The board"): each is pulled up to 5 V and its
// switch pulls it to GND when closed, as the buttons are wired (001_*.txt:845-853, 858-866).
// Pin k is bit k of the port, in the documented order: X min, X max, Y min, Y max, Z min, Z max.
TEST(Unit3Board, EndstopPinsAreActiveLow) {
  EXPECT_EQ(u::endstops_from_pins(0x3F), 0);     // all six high: every switch open
  EXPECT_EQ(u::endstops_from_pins(0xFF), 0);     // the port's bits 6 and 7 are no endstops
  EXPECT_EQ(u::endstops_from_pins(0x00), 0x3F);  // all six low: all closed
  EXPECT_EQ(u::endstops_from_pins(0xC0), 0x3F);
  for (int pin = 0; pin < 6; ++pin) {
    EXPECT_EQ(u::endstops_from_pins(static_cast<std::uint8_t>(0x3F & ~(1 << pin))), 1 << pin) << pin;
  }
  // X's minimum switch closed, its pin (0) low: X towards it is refused, away from it runs.
  Rig r;
  r.in.endstops = u::endstops_from_pins(0x3E);
  r.run(1);
  r.send("D---;X000000000000320;");
  EXPECT_EQ(r.rx, "E23;");
  r.send("D+++;X000000000000320;");
  r.settle();
  EXPECT_EQ(r.unit.axis(0).counter, 320);
  // Every pin high: nothing is closed, X runs back down.
  r.in.endstops = u::endstops_from_pins(0x3F);
  r.run(1);  // the unit reads its inputs in the tick
  r.send("D---;X000000000000320;");
  r.settle();
  EXPECT_EQ(r.unit.axis(0).counter, 0);
}

// docs/unit3.md "The menu": the stick drives the axes in the POSITIONS window only; in MENU,
// STEP SIZE and THREAD TYPE it reads as centred (an axis it runs ramps down one entry per 10 ms
// and stops from entry 0); PC moves run in every window.
TEST(Unit3Board, StickDrivesOnlyInThePositionsWindow) {
  Rig r;
  r.unit.press(Button::Enter);  // MENU
  r.in.adc[0] = 1023;
  r.run(200);
  EXPECT_EQ(r.pulses[0], 0U);
  EXPECT_FALSE(r.unit.out(0).running);
  r.unit.press(Button::Enter);  // STEP SIZE
  r.run(200);
  EXPECT_EQ(r.pulses[0], 0U);
  r.unit.press(Button::Back);  // MENU (saves the unchanged settings)
  r.unit.press(Button::Back);  // POSITIONS: the stick drives
  r.run(400);
  EXPECT_EQ(r.unit.axis(0).entry, 31);
  EXPECT_EQ(r.unit.axis(0).source, u::Source::Joystick);
  r.unit.press(Button::Enter);  // MENU while X runs at the top entry, the stick still full up
  int entry = r.unit.axis(0).entry;
  int ms = 0;
  for (; ms < 1000 && r.unit.out(0).running; ++ms) {
    r.run(1);
    if (!r.unit.out(0).running) break;
    EXPECT_LE(entry - r.unit.axis(0).entry, 1);
    EXPECT_LE(r.unit.axis(0).entry, entry);
    entry = r.unit.axis(0).entry;
  }
  EXPECT_FALSE(r.unit.out(0).running);
  EXPECT_EQ(entry, 0);    // it stopped from the start speed
  EXPECT_GE(ms, 31 * 10);  // 31 entries down, 10 ms each
  const auto stopped = r.pulses[0];
  r.run(500);
  EXPECT_EQ(r.pulses[0], stopped);
  r.send("D+++;Y000000000000320;");  // a PC move in MENU runs
  r.settle();
  EXPECT_EQ(r.unit.axis(1).counter, 320);
  r.unit.press(Button::Back);  // POSITIONS again: the stick, still full up, drives X
  r.run(50);
  EXPECT_TRUE(r.unit.out(0).running);
}

TEST(Unit3Board, MenuSaveWritesEepromOnceAndSendsTheSettings) {
  Rig r;
  for (const Button b : {Button::Enter, Button::Enter, Button::Right, Button::Right, Button::Back}) r.unit.press(b);
  r.drain();
  EXPECT_EQ(r.rx, "M200;T444;");
  EXPECT_EQ(r.unit.eeprom_writes(), 1U);
  r.unit.press(Button::Enter);  // back into step size, no change
  r.unit.press(Button::Back);
  EXPECT_EQ(r.unit.eeprom_writes(), 1U);  // nothing changed, nothing written
  r.unit.press(Button::Down);   // the menu: thread
  r.unit.press(Button::Down);   // zero positions
  r.unit.press(Button::Enter);
  r.drain();
  EXPECT_NE(r.rx.find("X+000000000000000000;Y+000000000000000000;Z+000000000000000000;"), std::string::npos);
}

TEST(Unit3Board, RunningAxesReportEvery100ms) {
  Rig r;
  r.send("X000000000102400;");  // 3200 pulses: 0.3 s of climb, then 800 Hz for about 4 s
  r.run(1000);
  int reports = 0;
  for (const auto& s : r.replies()) reports += s[0] == 'X' ? 1 : 0;
  EXPECT_EQ(reports, 10);
}

// Any interleaving of PC lines, stick positions, endstops and buttons keeps the unit's
// safety rules, seen on its pins: the direction of a running axis changes only after it
// stood at entry 0; no pulse towards a closed endstop; the entry moves by at most one per
// tick boundary; every counter stays within the 18-digit range.
RC_GTEST_PROP(Unit3BoardProps, SafetyRulesHoldUnderAnyInputs, ()) {
  Rig r;
  const auto n = *rc::gen::inRange(1, 40);
  const std::vector<std::string> lines = {"D+++;", "D---;", "D+-+;", "X000000000003200;", "Y000000000000640;",
                                          "Z000000000000032;", "M000;", "M555;", "M234;", "C;", "G;", "X0000"};
  std::array<int, 3> entry{};
  std::array<int, 3> dir{1, 1, 1};
  std::array<bool, 3> running{};
  for (int i = 0; i < n; ++i) {
    switch (*rc::gen::inRange(0, 4)) {
      case 0: r.send(lines[*rc::gen::inRange<std::size_t>(0, lines.size())]); break;
      case 1: r.in.adc[*rc::gen::inRange<std::size_t>(0, 3)] = *rc::gen::inRange<std::uint16_t>(0, 1024); break;
      case 2: r.in.endstops = *rc::gen::inRange<std::uint8_t>(0, 64); break;
      default: r.unit.press(static_cast<Button>(*rc::gen::inRange(0, 6))); break;
    }
    const int ms = *rc::gen::inRange(1, 300);
    for (int t = 0; t < ms; ++t) {
      r.run(1);
      for (std::size_t a = 0; a < 3; ++a) {
        const auto& o = r.unit.out(a);
        const int e = r.unit.axis(a).entry;
        if (running[a] && o.running) {
          RC_ASSERT(std::abs(e - entry[a]) <= 1);
          if (o.dir != dir[a]) RC_ASSERT(entry[a] == 0);
        }
        if (o.pulses > 0) RC_ASSERT((r.in.endstops & u::endstop_bit(a, o.dir > 0)) == 0);
        RC_ASSERT(r.unit.axis(a).counter <= 999'999'999'999'999'999LL);
        RC_ASSERT(r.unit.axis(a).counter >= -999'999'999'999'999'999LL);
        entry[a] = e;
        dir[a] = o.dir;
        running[a] = o.running;
      }
    }
  }
}

}  // namespace
