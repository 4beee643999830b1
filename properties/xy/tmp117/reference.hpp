#pragma once
// The expectation for TMP117 codes, written from the datasheet and not from the driver:
// value = signed code * 1000 / 128 m°C as an exact fraction, rounded to the nearest m°C with
// halves away from zero (docs/sensors.md) by long division.
#include <cstdint>

namespace tmp117_test {

inline std::int64_t signed_code(std::uint32_t code) {
  return code >= 0x8000u ? std::int64_t{code} - 0x10000 : std::int64_t{code};
}

inline std::int64_t reference_mc(std::uint32_t code) {
  const std::int64_t num = signed_code(code) * 1000;
  const std::int64_t den = 128;
  const std::int64_t mag = num < 0 ? -num : num;
  std::int64_t whole = mag / den;
  const std::int64_t rem = mag % den;
  if (2 * rem >= den) whole += 1;
  return num < 0 ? -whole : whole;
}

}  // namespace tmp117_test
