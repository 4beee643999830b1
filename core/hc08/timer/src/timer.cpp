#include "core/hc08/timer/timer.hpp"

namespace ap::hc08_timer {

static_assert(tmod_at_hz(280) == 8776);   // 2 457 600 / 280 = 8 777.14 ticks
static_assert(tmod_at_hz(1700) == 1445);  // 1 445.65 -> 1 446 ticks

Reload reload(std::uint32_t speed_centi, hc08_drive::Drive d) {
  if (speed_centi == 0) return {Error::ZeroSpeed, 0, 0};
  if (speed_centi > kSpeedMax) return {Error::OutOfRange, 0, 0};
  const std::uint64_t steps = hc08_drive::steps_per_rev(d);
  // f = speed_centi * steps / 100 Hz; reject above the motor's maximum (exactly, in 1/100 Hz).
  if (speed_centi * steps > std::uint64_t{max_hz(d)} * 100U) return {Error::TooFast, 0, 0};
  // Period in ticks of BUSCLK / 2^ps: kBusHz * 100 / (speed_centi * steps * 2^ps), rounded.
  const std::uint64_t num = std::uint64_t{kBusHz} * 100U;
  for (std::uint8_t ps = 0; ps <= kMaxPs; ++ps) {
    const std::uint64_t den = speed_centi * steps << ps;
    const std::uint64_t period = (2U * num + den) / (2U * den);
    // At most 1700 Hz the period is at least 1 446 ticks, so period - 1 never underflows.
    if (period <= kPeriodMax) return {Error::None, ps, static_cast<std::uint16_t>(period - 1U)};
  }
  return {Error::TooSlow, 0, 0};
}

std::uint32_t min_speed(hc08_drive::Drive d) {
  // 0.01 rev/s fits in half step; in full step 0.01 needs 6 144 000 ticks > 64 x 65 536, 0.02
  // fits (docs/hc08.md "Timer"): at most two tries, and max_speed always fits.
  std::uint32_t s = 1;
  while (s < max_speed(d) && reload(s, d).error != Error::None) ++s;
  return s;
}

Fitted fit_speed(std::uint32_t speed_centi, hc08_drive::Drive d) {
  if (reload(speed_centi, d).error == Error::None) return {static_cast<std::uint16_t>(speed_centi), Adjust::None};
  if (speed_centi > max_speed(d)) return {static_cast<std::uint16_t>(max_speed(d)), Adjust::LoweredToMax};
  return {static_cast<std::uint16_t>(min_speed(d)), Adjust::RaisedToMin};
}

}  // namespace ap::hc08_timer
