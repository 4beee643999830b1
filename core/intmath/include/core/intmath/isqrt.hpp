// Integer square root for the core's geometry (no floating point on the Cortex-M4 path):
// the TMC2130 current scale (docs/tmc2130.md), arc radii (docs/interpolation.md), the
// look-ahead's unit vectors (docs/lookahead.md) and the path's arc limits (docs/cnc.md).
#pragma once

#include <cstdint>

namespace ap::intmath {

// floor(sqrt(n)) for every uint64 n, digit by digit (32 rounds): the result r is the largest
// with r^2 <= n, so r < 2^32.
[[nodiscard]] constexpr std::uint64_t isqrt(std::uint64_t n) {
  std::uint64_t root = 0;
  std::uint64_t bit = std::uint64_t{1} << 62;
  while (bit > n) bit >>= 2;
  while (bit != 0) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

}  // namespace ap::intmath
