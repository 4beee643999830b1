// TIM1's reload (core/hc08/timer) against seed 002 §5.3.1 and docs/hc08.md "Timer": BUSCLK
// 2 457 600 Hz [T], PS 0..6 [EXT], period TMOD + 1 ticks [EXT]. The expectations are computed
// here in floating point from those numbers, not read from the core.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/hc08/timer/timer.hpp"

namespace {

namespace t = ap::hc08_timer;
using ap::hc08_drive::Drive;

TEST(Hc08Timer, TheThesisWorkedValues) {
  // seed-002.md §6.5 (the period, TMOD + 1 here): 40 steps at 0.50 rev/s: PS 1, 61 440;
  // at 0.02 rev/s: PS 6, 48 000; 80 steps at 0.10 rev/s: PS 3, 38 400; at 21.25: PS 0, 1 446.
  auto r = t::reload(50, Drive::Full);
  EXPECT_EQ(r.ps, 1);
  EXPECT_EQ(r.tmod, 61439);
  r = t::reload(2, Drive::Full);
  EXPECT_EQ(r.ps, 6);
  EXPECT_EQ(r.tmod, 47999);
  r = t::reload(10, Drive::Half);
  EXPECT_EQ(r.ps, 3);
  EXPECT_EQ(r.tmod, 38399);
  r = t::reload(2125, Drive::Half);
  EXPECT_EQ(r.ps, 0);
  EXPECT_EQ(r.tmod, 1445);
  // 0.01 rev/s in full step is 0.4 Hz: 6 144 000 ticks, more than 65 536 x 64 (seed-002.md §6.5).
  EXPECT_EQ(t::reload(1, Drive::Full).error, t::Error::TooSlow);
  EXPECT_EQ(t::reload(1, Drive::Half).error, t::Error::None);
  EXPECT_EQ(t::reload(0, Drive::Full).error, t::Error::ZeroSpeed);
  EXPECT_EQ(t::reload(2001, Drive::Full).error, t::Error::TooFast);   // 800.4 Hz > 800 Hz
  EXPECT_EQ(t::reload(2000, Drive::Full).error, t::Error::None);      // 800 Hz exactly
  EXPECT_EQ(t::reload(2126, Drive::Half).error, t::Error::TooFast);   // 1700.8 Hz
  EXPECT_EQ(t::reload(10000, Drive::Half).error, t::Error::OutOfRange);
}

// The user's speed adjusted into the motor's range (002_*.txt:729: inputs checked "and adjusted
// where needed"; docs/hc08.md "Menu"): the range ends from Tab. 3.1's maximum operating
// frequencies, 800 Hz / 40 steps = 20.00 rev/s and 1700 Hz / 80 = 21.25 rev/s, and from the timer,
// 0.02 rev/s full step (0.01 does not fit, above) and 0.01 half step.
TEST(Hc08Timer, FitSpeedIsTheNearestSpeedTheMotorMakes) {
  EXPECT_EQ(t::max_speed(Drive::Full), 2000U);
  EXPECT_EQ(t::max_speed(Drive::Half), 2125U);
  EXPECT_EQ(t::min_speed(Drive::Full), 2U);
  EXPECT_EQ(t::min_speed(Drive::Half), 1U);
  const auto fit = [](std::uint32_t v, Drive d, std::uint16_t want, t::Adjust how) {
    const t::Fitted f = t::fit_speed(v, d);
    EXPECT_EQ(f.speed_centi, want) << v;
    EXPECT_EQ(f.adjust, how) << v;
  };
  fit(100, Drive::Full, 100, t::Adjust::None);
  fit(2000, Drive::Full, 2000, t::Adjust::None);
  fit(2001, Drive::Full, 2000, t::Adjust::LoweredToMax);
  fit(2200, Drive::Full, 2000, t::Adjust::LoweredToMax);
  fit(9999, Drive::Full, 2000, t::Adjust::LoweredToMax);
  fit(10000, Drive::Full, 2000, t::Adjust::LoweredToMax);
  fit(1, Drive::Full, 2, t::Adjust::RaisedToMin);
  fit(0, Drive::Full, 2, t::Adjust::RaisedToMin);
  fit(2, Drive::Full, 2, t::Adjust::None);
  fit(0, Drive::Half, 1, t::Adjust::RaisedToMin);
  fit(1, Drive::Half, 1, t::Adjust::None);
  fit(2125, Drive::Half, 2125, t::Adjust::None);
  fit(2126, Drive::Half, 2125, t::Adjust::LoweredToMax);
  // Every four-digit speed: the nearer end of the documented range, and kept inside it.
  for (std::uint32_t v = 0; v <= 9999; ++v) {
    for (const Drive d : {Drive::Full, Drive::Half}) {
      const std::uint32_t lo = d == Drive::Full ? 2 : 1;
      const std::uint32_t hi = d == Drive::Full ? 2000 : 2125;
      const t::Fitted f = t::fit_speed(v, d);
      const std::uint32_t want = v < lo ? lo : v > hi ? hi : v;
      ASSERT_EQ(f.speed_centi, want) << v;
      ASSERT_EQ(f.adjust, v < lo ? t::Adjust::RaisedToMin : v > hi ? t::Adjust::LoweredToMax : t::Adjust::None) << v;
    }
  }
}

// Every speed 0.01 .. 99.99 rev/s in both drive types: the error is typed exactly where the
// hardware cannot make the speed; otherwise PS is the smallest that fits, TMOD + 1 is the
// nearest period, and the frequency error is within half a tick. The worst error is printed
// (docs/hc08.md "Timer" quotes it) and bounded.
TEST(Hc08Timer, EverySpeedInBothDriveTypes) {
  for (const Drive d : {Drive::Full, Drive::Half}) {
    const double steps = d == Drive::Full ? 40.0 : 80.0;
    const double fmax = d == Drive::Full ? 800.0 : 1700.0;
    double worst = 0.0;
    unsigned worst_at = 0, made = 0;
    for (unsigned v = 1; v <= 9999; ++v) {
      const double f = v / 100.0 * steps;
      const double ticks = 2457600.0 / f;
      const auto r = t::reload(v, d);
      if (f > fmax + 1e-9) {
        ASSERT_EQ(r.error, t::Error::TooFast) << v;
        continue;
      }
      if (ticks / 64.0 > 65536.5) {
        ASSERT_EQ(r.error, t::Error::TooSlow) << v;
        continue;
      }
      ASSERT_EQ(r.error, t::Error::None) << v;
      ++made;
      const double div = std::ldexp(1.0, r.ps);
      ASSERT_LE(r.ps, 6);
      ASSERT_LE(std::llround(ticks / div), 65536) << v;
      if (r.ps > 0) {
        ASSERT_GT(std::llround(ticks / std::ldexp(1.0, r.ps - 1)), 65536) << v << ": a smaller PS fits";
      }
      const double period = (r.tmod + 1.0) * div;
      ASSERT_LE(std::fabs(period / div - ticks / div), 0.5 + 1e-9) << v;
      const double err = std::fabs(2457600.0 / period - f) / f;
      if (err > worst) {
        worst = err;
        worst_at = v;
      }
    }
    std::printf("%s step: %u speeds made, worst frequency error %.4f %% at %u.%02u rev/s\n",
                d == Drive::Full ? "full" : "half", made, worst * 100, worst_at / 100, worst_at % 100);
    // Half a tick of the shortest period (1 446 ticks at 1700 Hz, 3 072 at 800 Hz).
    EXPECT_LT(worst, d == Drive::Full ? 0.5 / 3072 + 1e-6 : 0.5 / 1445 + 1e-6);
    EXPECT_EQ(made, d == Drive::Full ? 2000U - 1U : 2125U);  // full: 0.02 .. 20.00; half: 0.01 .. 21.25
  }
}

TEST(Hc08Timer, RampStepsBy64TicksTowardsItsGoal) {
  const std::uint16_t start = t::tmod_at_hz(280);
  EXPECT_EQ(start, 8776);  // 2 457 600 / 280 = 8 777.1 ticks
  EXPECT_EQ(t::ramp_step(start, 3071, false, Drive::Full), start - 64);
  EXPECT_EQ(t::ramp_step(3100, 3071, false, Drive::Full), 3071);  // never past the goal
  EXPECT_EQ(t::ramp_step(3071, 3071, true, Drive::Full), 3071 + 64);  // stopping: down to the start
  EXPECT_EQ(t::ramp_step(start - 10, 3071, true, Drive::Full), start);
  EXPECT_EQ(t::steps_to_start(3071, Drive::Full), (8776U - 3071U + 63U) / 64U);
}

}  // namespace
