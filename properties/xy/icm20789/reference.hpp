#pragma once
// The expected rotation, written from the datasheet and not from the integrator: the sum S of
// every raw sample so far (exact, unwrapped), each sample lasting 1 ms, at the sensitivity of
// DS-000169 Table 1 given in tenths of an LSB per °/s (1310, 655, 328, 164). The angle is
// S * 10 / sens10 m°, floored, taken modulo 360000 (floor division and a non-negative
// remainder, so negative sums wrap below 360000).
#include <cstdint>

namespace icm_test {

inline std::int64_t sensitivity_tenths(int fs_sel) {
  switch (fs_sel) {
    case 0: return 1310;  // ±250 °/s: 131 LSB/(°/s)
    case 1: return 655;   // ±500 °/s: 65.5
    case 2: return 328;   // ±1000 °/s: 32.8
    default: return 164;  // ±2000 °/s: 16.4
  }
}

inline std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

inline std::int64_t reference_mdeg(std::int64_t sum_raw, int fs_sel) {
  const std::int64_t m = floor_div(sum_raw * 10, sensitivity_tenths(fs_sel));
  const std::int64_t r = m % 360000;
  return r < 0 ? r + 360000 : r;
}

}  // namespace icm_test
