#pragma once
// Motor current, equation (7-1) of the thesis / datasheet 9:
//   I_RMS = (CS + 1) / 32 * V_FS / (R_sense + 20 mOhm) / sqrt(2)
// in integers: current in mA, R_sense in mOhm, V_FS in mV. sqrt(2) is irrational, so the
// result is computed by comparing squares, which makes it exact: current_ma() is the true
// value rounded to the nearest mA (a tie is impossible: the true value is irrational unless
// it is 0), and cs_for_current() is the largest CS whose true current does not exceed the
// target (never more current than asked for).
#include <cstdint>

#include "core/intmath/isqrt.hpp"

#include "core/xy/tmc2130/result.hpp"

namespace ap::xy_tmc2130::current {

// Full-scale sense voltages (datasheet 9, CHOPCONF.vsense).
inline constexpr std::uint32_t kVfsLowSensitivityMv = 320;   // vsense = 0
inline constexpr std::uint32_t kVfsHighSensitivityMv = 180;  // vsense = 1
inline constexpr std::uint32_t kRsenseOffsetMohm = 20;        // internal resistance term

// The thesis's board (seed §4.10): R_sense is not given there; 110 mOhm is the value of the
// common breakout boards and the one the seed's worked example uses. I_RUN = 12.
inline constexpr std::uint32_t kThesisRsenseMohm = 110;
inline constexpr bool kThesisVsense = false;
inline constexpr std::uint8_t kThesisIrun = 12;

// Documented input ranges; everything else is CurrentOutOfRange.
inline constexpr std::uint32_t kMinRsenseMohm = 1;
inline constexpr std::uint32_t kMaxRsenseMohm = 1000;
inline constexpr std::uint32_t kMaxCurrentMa = 10000;
inline constexpr std::uint8_t kMaxCs = 31;

constexpr std::uint32_t vfs_mv(bool vsense) {
  return vsense ? kVfsHighSensitivityMv : kVfsLowSensitivityMv;
}

namespace detail {
using ::ap::intmath::isqrt;
// Numerator N = (CS+1) * V_FS * 1000 (<= 32 * 320 * 1000 = 1.024e7) and denominator
// D = 32 * (R + 20) (<= 32 * 1020 = 32640), so I = N / (D * sqrt 2) in mA.
constexpr std::uint64_t numerator(std::uint32_t cs, bool vsense) {
  return std::uint64_t{cs + 1u} * vfs_mv(vsense) * 1000u;
}
constexpr std::uint64_t denominator(std::uint32_t rsense_mohm) {
  return std::uint64_t{32u} * (rsense_mohm + kRsenseOffsetMohm);
}
}  // namespace detail

// I_RMS in mA, rounded to nearest. With s = 2I = sqrt(2) N / D:
// round(I) = floor((floor(s) + 1) / 2) and floor(s) = isqrt(floor(2 N^2 / D^2)).
// 2 N^2 <= 2.1e14, far inside uint64.
constexpr Result<std::uint32_t> current_ma(std::uint8_t cs, bool vsense, std::uint32_t rsense_mohm) {
  if (cs > kMaxCs || rsense_mohm < kMinRsenseMohm || rsense_mohm > kMaxRsenseMohm) {
    return Error::CurrentOutOfRange;
  }
  const std::uint64_t n = detail::numerator(cs, vsense);
  const std::uint64_t d = detail::denominator(rsense_mohm);
  const std::uint64_t s = detail::isqrt((2u * n * n) / (d * d));
  return static_cast<std::uint32_t>((s + 1u) / 2u);
}

// Largest CS (0..31) whose true current is <= target. A target below CS = 0's current, or
// outside the documented ranges, is CurrentOutOfRange; above CS = 31 it is CS = 31, because
// 31 is then the largest CS that does not exceed the target.
// CS + 1 <= I D sqrt2 / (V_FS 1000)  =>  CS + 1 = floor(isqrt(2 I^2 D^2) / (V_FS 1000)).
constexpr Result<std::uint8_t> cs_for_current(std::uint32_t target_ma, bool vsense,
                                              std::uint32_t rsense_mohm) {
  if (target_ma > kMaxCurrentMa || rsense_mohm < kMinRsenseMohm || rsense_mohm > kMaxRsenseMohm) {
    return Error::CurrentOutOfRange;
  }
  const std::uint64_t d = detail::denominator(rsense_mohm);
  const std::uint64_t i = target_ma;
  const std::uint64_t steps = detail::isqrt(2u * i * i * d * d) / (std::uint64_t{vfs_mv(vsense)} * 1000u);
  if (steps == 0) return Error::CurrentOutOfRange;
  return static_cast<std::uint8_t>(steps > 32u ? kMaxCs : steps - 1u);
}

}  // namespace ap::xy_tmc2130::current
