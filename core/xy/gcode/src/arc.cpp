// Exact arc radius check without sqrt or floating point (docs/gcode.md §Arcs). The squared
// terms reach 2^102, beyond 64 bits, and the Cortex-M4 has no __int128, so products are
// compared as 128-bit values built from 32-bit halves.
#include "core/xy/gcode/arc.hpp"

namespace ap::xy_gcode {
namespace {

struct Wide {
  std::uint64_t hi;
  std::uint64_t lo;
};

Wide mul(std::uint64_t a, std::uint64_t b) {
  const std::uint64_t a0 = a & 0xFFFF'FFFFU;
  const std::uint64_t a1 = a >> 32;
  const std::uint64_t b0 = b & 0xFFFF'FFFFU;
  const std::uint64_t b1 = b >> 32;
  const std::uint64_t p00 = a0 * b0;
  const std::uint64_t p01 = a0 * b1;
  const std::uint64_t p10 = a1 * b0;
  const std::uint64_t p11 = a1 * b1;
  const std::uint64_t mid = (p00 >> 32) + (p01 & 0xFFFF'FFFFU) + (p10 & 0xFFFF'FFFFU);
  return {p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32), (mid << 32) | (p00 & 0xFFFF'FFFFU)};
}

bool greater(Wide x, Wide y) { return x.hi > y.hi || (x.hi == y.hi && x.lo > y.lo); }

// grbl's constants (gcode.c): 0.005 mm, 0.5 mm, 0.1 %.
constexpr std::uint64_t kMinToleranceUm = 5;
constexpr std::uint64_t kMaxToleranceUm = 500;

bool gap_exceeds(std::uint64_t a, std::uint64_t b, std::uint64_t t) {
  return sqrt_gap_exceeds(a, b, t) || sqrt_gap_exceeds(b, a, t);
}

// |sqrt(b) - sqrt(a)| > sqrt(a) / 1000  <=>  1e6 b > 1001^2 a  or  1e6 b < 999^2 a.
bool relative_gap_exceeds(std::uint64_t a, std::uint64_t b) {
  const Wide lhs = mul(1'000'000U, b);
  return greater(lhs, mul(1001U * 1001U, a)) || greater(mul(999U * 999U, a), lhs);
}

}  // namespace

// sqrt(b) > sqrt(a) + t  <=>  b - a - t^2 > 2 t sqrt(a)  <=>  D > 0 and D^2 > 4 t^2 a.
bool sqrt_gap_exceeds(std::uint64_t a, std::uint64_t b, std::uint64_t t) {
  const std::uint64_t t2 = t * t;
  if (b <= a + t2) return false;
  const std::uint64_t d = b - a - t2;
  return greater(mul(d, d), mul(4U * t2, a));
}

bool radius_mismatch(std::uint64_t r2_start, std::uint64_t r2_end) {
  if (!gap_exceeds(r2_start, r2_end, kMinToleranceUm)) return false;
  return gap_exceeds(r2_start, r2_end, kMaxToleranceUm) || relative_gap_exceeds(r2_start, r2_end);
}

}  // namespace ap::xy_gcode
