#pragma once
// TIM1 of the HC08 unit (seed 002 §5.3.1-5.3.2, docs/hc08.md "Timer"): BUSCLK through a
// 2^PS prescaler into a 16-bit counter that restarts after TMOD; each match switches the
// coils once. Integer-only; speed in 0.01 rev/s, the resolution the thesis states.
#include <cstdint>

#include "core/hc08/drive/drive.hpp"

namespace ap::hc08_timer {

inline constexpr std::uint32_t kBusHz = 2'457'600;  // 9.8304 MHz / 4, or 300 x 32 768 Hz / 4 [T §4.5]
inline constexpr std::uint8_t kMaxPs = 6;           // the prescaler divides by 1..64 [EXT: HC08 TIM]
inline constexpr std::uint32_t kPeriodMax = 65536;  // TMOD <= 0xFFFF, period TMOD + 1 ticks [EXT]
inline constexpr std::uint32_t kSpeedMax = 9999;    // four digits, 99.99 rev/s [T §4.3]

// Start and maximum operating frequencies of the SMR 300-100-RI/24 [T Tab. 3.1]: the catalogue's
// maximum start frequency is the start frequency (STARTFREQ4/8, whose values the thesis left on
// its CD) [D].
constexpr std::uint32_t start_hz(hc08_drive::Drive d) { return d == hc08_drive::Drive::Full ? 280 : 560; }
constexpr std::uint32_t max_hz(hc08_drive::Drive d) { return d == hc08_drive::Drive::Full ? 800 : 1700; }

enum class Error : std::uint8_t {
  None = 0,
  ZeroSpeed,   // 0.00 rev/s: no period
  TooSlow,     // the period does not fit 16 bits even at /64 (e.g. 0.01 rev/s in full step)
  TooFast,     // above the motor's maximum operating frequency
  OutOfRange,  // more than four digits
};

struct Reload {
  Error error = Error::None;
  std::uint8_t ps = 0;      // prescaler exponent: BUSCLK / 2^ps
  std::uint16_t tmod = 0;   // the match value; the period is tmod + 1 ticks of BUSCLK / 2^ps
};

// The thesis's rule with its "prescaler^2" read as 2^PS [D]: the smallest PS whose period
// fits 16 bits (the finest resolution), TMOD + 1 the period rounded to the nearest tick
// (the thesis's TMOD = BUSCLK / (2^PS speed steps) is the period; the HC08 counts TMOD + 1).
Reload reload(std::uint32_t speed_centi, hc08_drive::Drive d);

// The speeds the motor can be run at in drive type d, in 0.01 rev/s (docs/hc08.md "Timer"): up
// to its maximum operating frequency [T Tab. 3.1] (800 Hz / 40 = 20.00 rev/s full step, 1700 Hz
// / 80 = 21.25 rev/s half step), down to the slowest whose period fits 16 bits at /64 (0.02 rev/s
// full step, 0.01 half step).
constexpr std::uint32_t max_speed(hc08_drive::Drive d) { return max_hz(d) * 100U / hc08_drive::steps_per_rev(d); }
std::uint32_t min_speed(hc08_drive::Drive d);

// How fit_speed changed a speed.
enum class Adjust : std::uint8_t {
  None = 0,      // the motor can make it: kept
  RaisedToMin,   // 0 or too slow for the timer: min_speed
  LoweredToMax,  // above the motor's maximum (or past four digits): max_speed
};
struct Fitted {
  std::uint16_t speed_centi = 0;  // always one reload() makes in this drive type
  Adjust adjust = Adjust::None;
};
// A speed the user entered, brought into what the motor can make: the thesis checks the inputs
// and adjusts them where needed to fit the motor's properties (002_*.txt:729, docs/hc08.md
// "Menu"). The nearest end of [min_speed, max_speed].
Fitted fit_speed(std::uint32_t speed_centi, hc08_drive::Drive d);

// The period of a frequency in BUSCLK ticks at PS = 0 (every ramped speed is above the start
// frequency, whose period fits 16 bits: 2 457 600 / 280 = 8 777).
constexpr std::uint16_t tmod_at_hz(std::uint32_t hz) {
  return static_cast<std::uint16_t>((kBusHz + hz / 2U) / hz - 1U);
}

// The ramp [T §5.3.2]: "subtracting a constant from TMOD at every motor step" (accelStep,
// value on the CD). Here 64 ticks per step [D]: 280 -> 800 Hz in 90 steps, 560 -> 1700 Hz in 46.
// And the ramp-down the thesis lacks: the same constant added per step until the start
// frequency, below which the motor may stop or reverse (docs/hc08.md "Ramp").
inline constexpr std::uint16_t kAccelStep = 64;

struct Ramp {
  std::uint16_t tmod = 0;  // TMOD now (PS = 0 while ramping)
};

// Steps the ramp needs to come down from tmod to the start frequency.
constexpr std::uint32_t steps_to_start(std::uint16_t tmod, hc08_drive::Drive d) {
  const std::uint16_t start = tmod_at_hz(start_hz(d));
  return tmod >= start ? 0U : (static_cast<std::uint32_t>(start - tmod) + kAccelStep - 1U) / kAccelStep;
}

// One step of the ramp towards `target` (a TMOD at PS = 0), never faster than the target nor,
// when `stopping`, past the start frequency's TMOD.
constexpr std::uint16_t ramp_step(std::uint16_t tmod, std::uint16_t target, bool stopping, hc08_drive::Drive d) {
  const std::uint16_t start = tmod_at_hz(start_hz(d));
  const std::uint16_t goal = stopping ? start : target;
  if (tmod > goal) return tmod - goal > kAccelStep ? static_cast<std::uint16_t>(tmod - kAccelStep) : goal;
  if (tmod < goal) return goal - tmod > kAccelStep ? static_cast<std::uint16_t>(tmod + kAccelStep) : goal;
  return tmod;
}

}  // namespace ap::hc08_timer
