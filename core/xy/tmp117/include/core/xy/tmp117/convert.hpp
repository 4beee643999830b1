#pragma once
// Temp_Result (and Temp_Offset / limit) code -> m°C, exact for every one of the 65536 codes
// (docs/sensors.md "TMP117: rounding").
//
// One LSB is 7.8125 m°C = 1000/128 = 125/16 m°C, codes are two's complement (datasheet 8.1.1),
// so the true value is code * 125 / 16 m°C: a multiple of 1/16 m°C in [-256000, 255992.1875].
// It is rounded to the nearest m°C, halves away from zero, so that t(-c) = -t(c) and the
// datasheet's whole-degree rows come out as written. Ties are exactly the codes = 8 (mod 16).
// Range: int16 code * 125 lies in [-4096000, 4095875], far inside int32; the result lies in
// [-256000, 255992].
#include <cstdint>

namespace ap::xy_tmp117 {

inline constexpr std::int32_t kMilliCelsiusPerLsbNum = 125;
inline constexpr std::int32_t kMilliCelsiusPerLsbDen = 16;

constexpr std::int32_t millicelsius(std::uint16_t code) {
  // The register is two's complement: bit 15 is the sign (-256 °C), not +256 °C.
  const std::int32_t signed_code = static_cast<std::int16_t>(code);
  const std::int32_t sixteenths = signed_code * kMilliCelsiusPerLsbNum;
  constexpr std::int32_t half = kMilliCelsiusPerLsbDen / 2;
  if (sixteenths >= 0) return (sixteenths + half) / kMilliCelsiusPerLsbDen;
  return -((-sixteenths + half) / kMilliCelsiusPerLsbDen);
}

inline constexpr std::int32_t kMinMilliCelsius = millicelsius(0x8000);  // -256000
inline constexpr std::int32_t kMaxMilliCelsius = millicelsius(0x7FFF);  //  255992

}  // namespace ap::xy_tmp117
