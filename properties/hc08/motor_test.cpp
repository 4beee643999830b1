// The motor (core/hc08/motor) against seed 002 §5.3 and docs/hc08.md "Motor", "Ramp", "Mode B".
// Start frequencies 280 / 560 Hz and maxima 800 / 1700 Hz [T Tab. 3.1]; BUSCLK 2 457 600 Hz.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "core/hc08/motor/motor.hpp"

namespace {

namespace mo = ap::hc08_motor;
using ap::hc08_drive::Drive;

constexpr std::uint32_t kBus = 2'457'600;
std::uint32_t start_period(Drive d) { return d == Drive::Full ? kBus / 280 : kBus / 560; }  // 8 777 / 4 388 ticks (floor)
std::uint32_t min_period(Drive d) { return d == Drive::Full ? kBus / 800 : kBus / 1700; }   // 3 072 / 1 445

struct Step {
  std::uint32_t period;  // ticks before this step
  int dir;  // the way this step turned
};

// Runs to rest (or `limit` steps), calling `at(i)` before each step.
template <class At>
std::vector<Step> run(mo::Motor& m, At at, int limit = 200000) {
  std::vector<Step> v;
  for (int i = 0; i < limit && m.running(); ++i) {
    at(i);
    const std::uint32_t p = m.period_ticks();
    const int d = m.dir();  // this step turns the way the motor faces before it
    m.on_match();
    v.push_back({p, d});
  }
  return v;
}
std::vector<Step> run(mo::Motor& m) {
  return run(m, [](int) {});
}

mo::Settings settings(mo::Mode mode, Drive d, std::uint16_t speed, std::uint16_t angle, bool right = true) {
  mo::Settings s;
  s.mode = mode;
  s.drive = d;
  s.speed_centi = speed;
  s.angle_deg = angle;
  s.right = right;
  return s;
}

TEST(Hc08Motor, ModeBNinetyDegrees) {
  // 90° = 10 full steps of 9°, 20 half steps of 4.5° [T Tab. 3.1].
  mo::Motor m;
  ASSERT_EQ(m.start(settings(mo::Mode::B, Drive::Full, 100, 90)), mo::Error::None);
  EXPECT_EQ(run(m).size(), 10U);
  EXPECT_EQ(m.angle_tenths(), 900);
  ASSERT_EQ(m.start(settings(mo::Mode::B, Drive::Half, 100, 90)), mo::Error::None);
  EXPECT_EQ(run(m).size(), 20U);
  EXPECT_EQ(m.angle_tenths(), 1800);
}

TEST(Hc08Motor, ASpeedTheTimerCannotMakeIsATypedErrorAndNothingMoves) {
  mo::Motor m;
  EXPECT_EQ(m.start(settings(mo::Mode::A, Drive::Full, 1, 0)), mo::Error::BadSpeed);
  EXPECT_EQ(m.last_timer_error(), ap::hc08_timer::Error::TooSlow);
  EXPECT_FALSE(m.running());
  EXPECT_FALSE(m.on_match());
  EXPECT_EQ(m.position_half(), 0);
  EXPECT_EQ(m.start(settings(mo::Mode::A, Drive::Full, 2100, 0)), mo::Error::BadSpeed);
  EXPECT_EQ(m.last_timer_error(), ap::hc08_timer::Error::TooFast);
}

// Mode B at any speed and angle: exactly the steps the angle makes; the first and the last
// step at most at the start frequency; never faster than the set speed or the motor's
// maximum; the period changes by at most the ramp's 64 ticks from step to step while above
// the start frequency.
RC_GTEST_PROP(Hc08MotorProps, ModeBStartsAndEndsAtTheStartFrequency, ()) {
  const Drive d = *rc::gen::element(Drive::Full, Drive::Half);
  const std::uint16_t speed = *rc::gen::oneOf(rc::gen::inRange<std::uint16_t>(2, d == Drive::Full ? 2001 : 2126),
                                              rc::gen::element<std::uint16_t>(2000, 2125, 700, 50));
  if (d == Drive::Full && speed > 2000) return;
  const std::uint16_t angle = *rc::gen::inRange<std::uint16_t>(0, 10000);
  mo::Motor m;
  RC_ASSERT(m.start(settings(mo::Mode::B, d, speed, angle, *rc::gen::arbitrary<bool>())) == mo::Error::None);
  const auto steps = run(m);
  const std::uint32_t spr = d == Drive::Full ? 40 : 80;
  RC_ASSERT(steps.size() == angle * spr / 360);
  const double f_set = speed / 100.0 * spr;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    RC_ASSERT(steps[i].period >= min_period(d));
    RC_ASSERT(kBus / static_cast<double>(steps[i].period) <= f_set * 1.001);
    if (i > 0 && steps[i].period < start_period(d) && steps[i - 1].period < start_period(d)) {
      RC_ASSERT(std::abs(static_cast<int>(steps[i].period) - static_cast<int>(steps[i - 1].period)) <= 64);
    }
  }
  if (!steps.empty()) {
    RC_ASSERT(steps.front().period >= start_period(d) || kBus / static_cast<double>(steps.front().period) <= f_set * 1.001);
    RC_ASSERT(steps.back().period >= start_period(d));
  }
}

// n moves of angle a end within one step of n·a (the remainder is carried, docs/hc08.md).
RC_GTEST_PROP(Hc08MotorProps, RepeatedMovesDoNotDrift, ()) {
  const Drive d = *rc::gen::element(Drive::Full, Drive::Half);
  const std::uint16_t a = *rc::gen::inRange<std::uint16_t>(0, 400);
  const int n = *rc::gen::inRange(1, 60);
  const bool right = *rc::gen::arbitrary<bool>();
  mo::Motor m;
  for (int i = 0; i < n; ++i) {
    RC_ASSERT(m.start(settings(mo::Mode::B, d, 500, a, right)) == mo::Error::None);
    run(m);
  }
  const double turned = static_cast<double>(m.position_half()) * 4.5 * (right ? 1 : -1);  // degrees
  RC_ASSERT(std::abs(turned - static_cast<double>(n) * a) < (d == Drive::Full ? 9.0 : 4.5));
  RC_ASSERT(turned <= static_cast<double>(n) * a + 1e-9);  // never past the commanded angle
}

// Mode A: a stop comes down to the start frequency before the last step, a reversal changes
// the direction only at or below it.
RC_GTEST_PROP(Hc08MotorProps, ModeAStopAndReversalDecelerateFirst, ()) {
  const Drive d = *rc::gen::element(Drive::Full, Drive::Half);
  const std::uint16_t speed = *rc::gen::inRange<std::uint16_t>(2, d == Drive::Full ? 2001 : 2126);
  mo::Motor m;
  RC_ASSERT(m.start(settings(mo::Mode::A, d, speed, 0)) == mo::Error::None);
  const int reverse_at = *rc::gen::inRange(0, 300);
  const int stop_at = reverse_at + *rc::gen::inRange(1, 300);
  const auto steps = run(
      m,
      [&](int i) {
        if (i == reverse_at) m.set_direction(false);
        if (i == stop_at) m.stop();
      },
      5000);
  RC_ASSERT(!m.running());
  for (std::size_t i = 1; i < steps.size(); ++i) {
    if (steps[i].dir != steps[i - 1].dir) RC_ASSERT(steps[i - 1].period >= start_period(d) && steps[i].period >= start_period(d));
  }
  RC_ASSERT(steps.back().period >= start_period(d) || kBus / static_cast<double>(steps.back().period) <= speed / 100.0 * (d == Drive::Full ? 40 : 80) * 1.001);
}

}  // namespace
