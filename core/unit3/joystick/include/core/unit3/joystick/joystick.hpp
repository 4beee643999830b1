#pragma once
// The unit's joystick: one 10-bit ADC reading per axis -> stop, or a direction and an index
// into the 32-entry ramp table (seed 001 §3.6, docs/unit3.md "The joystick").
//   dead band  500 <= ADC <= 524: the axis stops                        [T: "500-524"; both ends stop, D]
//   below      ADC < 500:  index = (512 - ADC) / 16, direction -1       [T: eq. 6; sign D]
//   above      ADC > 524:  index = (ADC - 524) / 16, direction +1       [T: eq. 7; sign D]
// Eq. 6 gives index 32 at ADC 0, one past the table (the thesis's firmware read past it):
// the index is clamped to 31 there [D], and `axisproof prove --profile unit3` proves every
// ADC value gives an index inside the table.
#include <cstdint>

namespace ap::unit3_joystick {

inline constexpr std::uint16_t kAdcMax = 1023;     // 10-bit ADC, AREF = 5 V [T]
inline constexpr std::uint16_t kDeadLow = 500;     // [T]
inline constexpr std::uint16_t kDeadHigh = 524;    // [T]
inline constexpr std::uint16_t kLowerZero = 512;   // eq. 6's constant [T]
inline constexpr std::uint16_t kCodesPerIndex = 16;  // eq. 6, 7 [T]
inline constexpr std::uint8_t kTableSize = 32;     // ramp table entries 0..31 [T]

struct Deflection {
  std::int8_t dir = 0;     // 0: stop (dead band); -1 below it, +1 above it
  std::uint8_t index = 0;  // ramp-table index 0..31, meaningful when dir != 0
  friend constexpr bool operator==(const Deflection&, const Deflection&) = default;
};

// Defined for every 16-bit input: a reading above kAdcMax (a glitch; the ADC cannot give one)
// is taken as kAdcMax.
constexpr Deflection deflection(std::uint16_t adc) {
  if (adc > kAdcMax) adc = kAdcMax;
  if (adc >= kDeadLow && adc <= kDeadHigh) return {};
  if (adc < kDeadLow) {
    const auto i = static_cast<std::uint8_t>((kLowerZero - adc) / kCodesPerIndex);
    return {-1, i < kTableSize ? i : static_cast<std::uint8_t>(kTableSize - 1)};
  }
  return {1, static_cast<std::uint8_t>((adc - kDeadHigh) / kCodesPerIndex)};
}

}  // namespace ap::unit3_joystick
