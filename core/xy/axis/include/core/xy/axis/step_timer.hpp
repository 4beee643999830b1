// STEP frequency -> TIM prescaler and auto-reload (thesis eq. 7-3 to 7-5, corrected: gap G17).
//
// f_STEP = f_clk / ((PSC + 1) * (ARR + 1)) with 16-bit PSC and ARR. The thesis floors PSC,
// which makes ARR + 1 >= 65536 (overflow) and PSC = -1 above f_clk / 65536 = 1220.7 Hz.
// Rounding PSC up instead gives the smallest prescaler whose ARR still fits 16 bits, i.e.
// the finest frequency resolution:
//   PSC = ceil(f_clk / (f * 65536)) - 1 = (f_clk - 1) / (f * 65536)
//   ARR = floor(f_clk / (f * (PSC + 1))) - 1
// Error bound (proved in docs/motion.md, checked for every f in range by axis_timer tests):
//   f <= f_real < f * (ARR + 2) / (ARR + 1),  i.e.  0 <= (f_real - f) / f < 1 / (ARR + 1),
// and ARR + 1 >= 32768 below 1221 Hz, ARR + 1 >= f_clk / f above (PSC = 0); for f <= 1e6
// (kSpeedMax) the relative error is < 1/80, for f <= 51200 it is < 1/1562.
#pragma once

#include <cstdint>
#include <optional>

namespace ap::xy_axis {

inline constexpr uint32_t kTimerClockHz = 80'000'000;
inline constexpr uint32_t kTimerRegMax = 65'535;
// Highest frequency with ARR >= 1 (a PWM period of two clocks).
inline constexpr uint32_t kStepFreqMax = kTimerClockHz / 2;

struct TimerSetting {
  uint16_t psc;
  uint16_t arr;
};

// f_hz in [1, kStepFreqMax]; 0 (timer stopped) and anything above have no setting.
// f * 65536 <= 4e7 * 65536 < 2^42: computed in uint64.
[[nodiscard]] constexpr std::optional<TimerSetting> step_timer(uint32_t f_hz) {
  if (f_hz == 0 || f_hz > kStepFreqMax) {
    return std::nullopt;
  }
  const uint64_t f = f_hz;
  const uint64_t psc = (uint64_t{kTimerClockHz} - 1) / (f * (uint64_t{kTimerRegMax} + 1));
  const uint64_t arr = uint64_t{kTimerClockHz} / (f * (psc + 1)) - 1;
  return TimerSetting{static_cast<uint16_t>(psc), static_cast<uint16_t>(arr)};
}

// Timer clocks per STEP period: (PSC + 1) * (ARR + 1) <= 2^32.
[[nodiscard]] constexpr uint64_t timer_period_clocks(TimerSetting t) {
  return (uint64_t{t.psc} + 1) * (uint64_t{t.arr} + 1);
}

// Realised frequency in mHz (integer, rounded down): <= 8e10 fits uint64.
[[nodiscard]] constexpr uint64_t realised_mhz(TimerSetting t) {
  return uint64_t{kTimerClockHz} * 1000 / timer_period_clocks(t);
}

// Compare value for a 50 % duty STEP pulse (duty unspecified in the thesis).
[[nodiscard]] constexpr uint16_t step_ccr(TimerSetting t) {
  return static_cast<uint16_t>((uint32_t{t.arr} + 1) / 2);
}

}  // namespace ap::xy_axis
