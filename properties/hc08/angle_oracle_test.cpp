// The HC08 unit's angle arithmetic (core/hc08/motor, core/hc08/board) against an independent
// oracle: the reference model models/hc08/angle_model.hpp, written from the thesis (seed 002,
// 002_*.txt l. 462-463 Tab. 3.1, l. 724, l. 768, l. 1063) and docs/hc08.md "Angle arithmetic"
// without the unit's code, and the rotor's position read back from the coils alone
// (CoilTracker). Random sequences of mode A runs and mode B moves both ways, stopped or not,
// and changes of drive type: after every step the motor's angle is the angle of where the coils
// put the rotor, and after every move the position, the angle and each mode B move's number of
// steps are the model's, the display's included.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>

#include "core/hc08/board/board.hpp"
#include "core/hc08/motor/motor.hpp"
#include "models/hc08/angle_model.hpp"

namespace {

namespace mo = ap::hc08_motor;
namespace am = ap::model::hc08;
namespace b = ap::hc08_board;
using ap::hc08_drive::Drive;

mo::Settings settings(mo::Mode mode, bool half, std::uint16_t speed, std::uint16_t angle, bool right) {
  mo::Settings s;
  s.mode = mode;
  s.drive = half ? Drive::Half : Drive::Full;
  s.speed_centi = speed;
  s.angle_deg = angle;
  s.right = right;
  return s;
}

// The display's angle left of the start, worked by hand from the thesis's step angles
// (002_*.txt l. 463: 9° full, 4.5° half) and its 0-360° display (l. 768): the angle shown is
// where the rotor points, so one full step left of 0 is 351.0°, one half step 355.5°.
TEST(Hc08AngleOracle, TheModelsDisplayAngleLeftOfTheStart) {
  EXPECT_EQ(am::display_tenths(0), 0);
  EXPECT_EQ(am::display_tenths(1), 45);
  EXPECT_EQ(am::display_tenths(-1), 3555);
  EXPECT_EQ(am::display_tenths(-2), 3510);
  EXPECT_EQ(am::display_tenths(-80), 0);     // one turn left: back at 0.0
  EXPECT_EQ(am::display_tenths(-81), 3555);
  EXPECT_EQ(am::display_tenths(-82), 3510);  // 369° left = 41 full steps
  EXPECT_EQ(am::display_tenths(79), 3555);
  EXPECT_EQ(am::display_tenths(80 * 125 + 2), 90);  // 9999° right in half steps and more
  EXPECT_EQ(am::display_tenths(-(80 * 125 + 2)), 3510);
}

// Mode B's carried remainder across a drive type change (docs/hc08.md "Angle arithmetic"):
// 5° in four-step is no whole 9° step, so nothing turns and 5° stays commanded; in eight-step
// a further 5° makes 10° commanded, two 4.5° steps (9°), never past 10°.
TEST(Hc08AngleOracle, TheModelCarriesTheRemainderAcrossADriveChange) {
  am::AngleModel a;
  EXPECT_EQ(a.plan_b(true, 5), 0);
  a.finish_b(0);
  EXPECT_EQ(a.set_drive(true), 0);
  EXPECT_EQ(a.plan_b(true, 5), 2);
  a.finish_b(2);
  EXPECT_EQ(a.position_half(), 2);
  EXPECT_EQ(a.angle_tenths(), 90);
  // Back to four-step at an even half step: no move; 3° more right (13° commanded, the rotor at
  // 9°) is no whole step; 14° left (-1° commanded) from 9° is one 9° step to 0°, not past -1°.
  EXPECT_EQ(a.set_drive(false), 0);
  EXPECT_EQ(a.plan_b(true, 3), 0);
  a.finish_b(0);
  EXPECT_EQ(a.plan_b(false, 14), 1);
  a.finish_b(1);
  EXPECT_EQ(a.position_half(), 0);
  // Eight-step, 1° left (-2° commanded): no whole 4.5° step; four-step from an even position:
  // no move.
  a.set_drive(true);
  EXPECT_EQ(a.plan_b(false, 1), 0);
  a.finish_b(0);
  // Eight-step, 4° left: -6° commanded, one half step to -4.5° (355.5°), not past -6°.
  EXPECT_EQ(a.plan_b(false, 4), 1);
  a.finish_b(1);
  EXPECT_EQ(a.angle_tenths(), 3555);
  // To four-step from the odd position: half a step forward, to 0 (docs/hc08.md "Excitation").
  EXPECT_EQ(a.set_drive(false), 1);
  EXPECT_EQ(a.position_half(), 0);
}

// The same on the motor: 5° in four-step turns nothing; 5° more in eight-step is 10°
// commanded, two half steps (9.0°), not the one step 5° alone would make.
TEST(Hc08AngleOracle, TheMotorCarriesTheRemainderAcrossADriveChange) {
  mo::Motor m;
  ASSERT_EQ(m.start(settings(mo::Mode::B, false, 100, 5, true)), mo::Error::None);
  EXPECT_FALSE(m.running());
  ASSERT_TRUE(m.set_drive(Drive::Half));
  ASSERT_EQ(m.start(settings(mo::Mode::B, true, 100, 5, true)), mo::Error::None);
  int n = 0;
  while (m.running() && n < 100) n += m.on_match() ? 1 : 0;
  EXPECT_EQ(n, 2);
  EXPECT_EQ(m.angle_tenths(), 90);
}

// A mode B move turns the set way or not at all (002_*.txt l. 55, 724: "the angle by which the
// shaft turns" with the other settings, the direction among them, l. 726): 5° left in four-step
// is no whole step and stays commanded; 1° right then leaves -4° commanded, left of the rotor:
// the right move turns nothing; it must not take a 9° step left to get "not past" -4°.
TEST(Hc08AngleOracle, AModeBMoveNeverTurnsAgainstItsDirection) {
  am::AngleModel a;
  EXPECT_EQ(a.plan_b(false, 5), 0);
  a.finish_b(0);
  EXPECT_EQ(a.plan_b(true, 1), 0);
  a.finish_b(0);
  mo::Motor m;
  ASSERT_EQ(m.start(settings(mo::Mode::B, false, 100, 5, false)), mo::Error::None);
  EXPECT_FALSE(m.running());
  ASSERT_EQ(m.start(settings(mo::Mode::B, false, 100, 1, true)), mo::Error::None);
  int n = 0;
  while (m.running() && n < 100) n += m.on_match() ? 1 : 0;
  EXPECT_EQ(n, 0);
  EXPECT_EQ(m.position_half(), 0);
  EXPECT_EQ(m.angle_tenths(), 0);
}

// The motor left of its start, by hand: a mode B move of 9° left in four-step shows 351.0°; a
// turn and a step (369°) left shows the same; 5° left in eight-step is one half step, 355.5°.
TEST(Hc08AngleOracle, TheMotorsAngleLeftOfTheStart) {
  const auto run = [](mo::Motor& m) {
    int n = 0;
    while (m.running() && n < 100000) n += m.on_match() ? 1 : 0;
    return n;
  };
  mo::Motor m;
  ASSERT_EQ(m.start(settings(mo::Mode::B, false, 100, 9, false)), mo::Error::None);
  EXPECT_EQ(run(m), 1);
  EXPECT_EQ(m.angle_tenths(), 3510);
  ASSERT_EQ(m.start(settings(mo::Mode::B, false, 100, 360, false)), mo::Error::None);
  EXPECT_EQ(run(m), 40);
  EXPECT_EQ(m.angle_tenths(), 3510);
  mo::Motor h;
  ASSERT_EQ(h.start(settings(mo::Mode::B, true, 100, 5, false)), mo::Error::None);
  EXPECT_EQ(run(h), 1);
  EXPECT_EQ(h.angle_tenths(), 3555);
}

// Runs the motor to rest; `stop_at` >= 0 asks it to stop before that step. Every step is fed to
// the coil tracker: it turns the way the move was set (the user's direction, 002_*.txt l. 726,
// l. 746), one step of the drive type, and the motor's angle is the coils'. Returns the steps.
std::int64_t run_checked(mo::Motor& m, am::CoilTracker& coils, int stop_at, bool right, bool half) {
  std::int64_t n = 0;
  for (int i = 0; m.running() && i < 100000; ++i) {
    if (i == stop_at) m.stop();
    const std::int64_t before = coils.position_half();
    if (m.on_match()) ++n;
    coils.feed(m.port());
    RC_ASSERT(coils.ok());
    RC_ASSERT(coils.position_half() - before == (right ? 1 : -1) * am::half_steps_per_step(half));
    RC_ASSERT(static_cast<int>(m.angle_tenths()) == coils.angle_tenths());
  }
  RC_ASSERT(!m.running());
  return n;
}

// The motor against the model: any sequence of drive changes, mode B moves (left or right,
// any angle, some stopped early by SET) and mode A runs.
RC_GTEST_PROP(Hc08AngleOracleProps, MotorFollowsTheModel, ()) {
  mo::Motor m;
  am::AngleModel model;
  am::CoilTracker coils;
  const int ops = *rc::gen::inRange(1, 40);
  for (int op = 0; op < ops; ++op) {
    const int kind = *rc::gen::inRange(0, 10);
    const bool right = *rc::gen::arbitrary<bool>();
    const std::uint16_t speed = *rc::gen::inRange<std::uint16_t>(2, 2001);  // both drive types make it
    if (kind < 2) {  // a drive change at rest
      const bool half = *rc::gen::arbitrary<bool>();
      RC_ASSERT(m.set_drive(half ? Drive::Half : Drive::Full));
      model.set_drive(half);
      coils.feed(m.port());
      RC_LOG() << "drive " << (half ? "half" : "full") << " -> " << model.position_half() << "\n";
    } else if (kind < 9) {  // mode B; a quarter of them change the drive type by the settings
      bool half = model.half();
      if (*rc::gen::inRange(0, 4) == 0) {
        half = *rc::gen::arbitrary<bool>();
        model.set_drive(half);
      }
      const auto angle = *rc::gen::oneOf(rc::gen::inRange<std::uint16_t>(0, 30), rc::gen::inRange<std::uint16_t>(0, 800),
                                         rc::gen::element<std::uint16_t>(0, 1, 4, 5, 9, 360, 9999));
      const bool stop_early = kind == 8;
      const std::int64_t want = model.plan_b(right, angle);
      RC_ASSERT(m.start(settings(mo::Mode::B, half, speed, angle, right)) == mo::Error::None);
      coils.feed(m.port());
      const std::int64_t got = run_checked(m, coils, stop_early ? *rc::gen::inRange(0, 20) : -1, right, half);
      RC_LOG() << "B " << (half ? "half " : "full ") << (right ? "right " : "left ") << angle << (stop_early ? " stopped" : "")
               << ": " << got << " of " << want << " steps -> " << m.position_half() << "\n";
      if (stop_early) {
        RC_ASSERT(got <= want);
      } else {
        RC_ASSERT(got == want);
      }
      model.finish_b(got);
    } else {  // mode A: one way, then SET
      RC_ASSERT(m.start(settings(mo::Mode::A, model.half(), speed, 0, right)) == mo::Error::None);
      const std::int64_t got = run_checked(m, coils, *rc::gen::inRange(0, 200), right, model.half());
      model.turned(right, got);
      RC_LOG() << "A " << (right ? "right " : "left ") << got << " steps -> " << m.position_half() << "\n";
    }
    RC_ASSERT(coils.position_half() == model.position_half());
    RC_ASSERT(m.position_half() == model.position_half());
    RC_ASSERT(static_cast<int>(m.angle_tenths()) == model.angle_tenths());
  }
}

// The board's display against the model, driven by the keys alone (docs/hc08.md "Menu"): mode,
// direction, drive type and angle set through the menu, SET starts and stops, the timer's
// matches step; back in S_DEF the display shows the model's angle with one decimal.
struct Unit {
  b::Board u;
  am::CoilTracker coils;
  void key(std::uint8_t code) {
    u.push_key(code);
    u.main_loop();
    coils.feed(u.port());  // a drive change at rest moves the coils without a step
  }
  void keys(std::uint8_t code, int n) {
    for (int i = 0; i < n; ++i) key(code);
  }
  std::int64_t run(int stop_at) {  // SET (stop) before match `stop_at` when >= 0
    std::int64_t n = 0;
    for (int i = 0; u.timer_running() && i < 100000; ++i) {
      if (i == stop_at) key(kSet);
      if (!u.timer_running()) break;
      if (u.timer_match()) ++n;
      u.main_loop();
      coils.feed(u.port());
    }
    return n;
  }
  // The kit's key codes (board_test.cpp): column bit | active-low row nibble.
  static constexpr std::uint8_t kSet = 0x2D, kLeft = 0x4D, kRight = 0x1D, kPlus = 0x2B, kMinus = 0x2E;
};

RC_GTEST_PROP(Hc08AngleOracleProps, BoardShowsTheModelsAngle, ()) {
  Unit t;
  am::AngleModel model;
  bool right = true;  // the power-up settings (docs/hc08.md "Power-up")
  const int ops = *rc::gen::inRange(1, 25);
  for (int op = 0; op < ops; ++op) {
    const int kind = *rc::gen::inRange(0, 6);
    if (kind == 0) {  // SET_DIRECT: PLUS right, MINUS left [T Tab. 4.3]
      right = *rc::gen::arbitrary<bool>();
      t.key(Unit::kRight);
      t.key(Unit::kRight);
      t.key(right ? Unit::kPlus : Unit::kMinus);
      t.keys(Unit::kLeft, 2);
      RC_LOG() << (right ? "right\n" : "left\n");
    } else if (kind == 1) {  // SET_DRIVE: PLUS eight-step, MINUS four-step [T Tab. 4.3]
      const bool half = *rc::gen::arbitrary<bool>();
      t.key(Unit::kRight);
      t.key(half ? Unit::kPlus : Unit::kMinus);
      t.key(Unit::kLeft);
      model.set_drive(half);
      RC_LOG() << "drive " << (half ? "half" : "full") << " -> " << model.position_half() << "\n";
    } else if (kind == 2) {  // SET_ANGLE: the editor, digit by digit, leftmost first
      const auto want = *rc::gen::oneOf(rc::gen::inRange<int>(0, 40), rc::gen::inRange<int>(0, 1000));
      t.keys(Unit::kRight, 4);
      t.key(Unit::kSet);
      const auto cur = t.u.menu().edit;
      const int d[4] = {want / 1000, want / 100 % 10, want / 10 % 10, want % 10};
      for (int i = 0; i < 4; ++i) {
        t.keys(Unit::kPlus, (d[i] - cur[static_cast<std::size_t>(i)] + 10) % 10);
        if (i < 3) t.key(Unit::kRight);
      }
      t.key(Unit::kSet);
      RC_ASSERT(static_cast<int>(t.u.settings().angle_deg) == want);
      t.keys(Unit::kLeft, 4);
      RC_LOG() << "angle " << want << "\n";
    } else if (kind <= 4) {  // mode B (MINUS in S_DEF), SET; some stopped by SET early
      t.key(Unit::kMinus);
      const bool stop_early = kind == 4 && *rc::gen::arbitrary<bool>();
      const std::int64_t want = model.plan_b(right, t.u.settings().angle_deg);
      t.key(Unit::kSet);
      const std::int64_t got = t.run(stop_early ? *rc::gen::inRange(0, 20) : -1);
      RC_LOG() << "B " << (right ? "right " : "left ") << (stop_early ? "stopped " : "") << got << " of " << want << " steps -> "
               << t.coils.position_half() << "\n";
      if (stop_early) {
        RC_ASSERT(got <= want);
      } else {
        RC_ASSERT(got == want);
      }
      model.finish_b(got);
    } else {  // mode A (PLUS in S_DEF), SET, some matches, SET
      t.key(Unit::kPlus);
      t.key(Unit::kSet);
      const std::int64_t got = t.run(*rc::gen::inRange(0, 200));
      model.turned(right, got);
      RC_LOG() << "A " << (right ? "right " : "left ") << got << " steps -> " << t.coils.position_half() << "\n";
    }
    RC_ASSERT(t.u.menu().state == ap::hc08_menu::State::Def);
    RC_ASSERT(!t.u.timer_running());
    RC_ASSERT(t.coils.ok());
    RC_ASSERT(t.coils.position_half() == model.position_half());
    RC_ASSERT(static_cast<int>(t.u.display().value) == model.angle_tenths());
    RC_ASSERT(t.u.display().point == 1);
  }
}

}  // namespace
