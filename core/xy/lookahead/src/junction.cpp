// Corner look-ahead (junction.hpp; docs/lookahead.md explains every decision and range).
#include "core/xy/lookahead/junction.hpp"

#include "core/intmath/isqrt.hpp"
#include "core/xy/lookahead/angle.hpp"

namespace ap::xy_lookahead {
namespace {

constexpr bool in_range(int64_t v) { return v >= -kComponentMax && v <= kComponentMax; }

constexpr Direction make(DirectionKind kind) { return Direction{0, 0, kind}; }

// Tangent at a point relative to the centre: CW (y, -x), CCW (-y, x) (docs/lookahead.md "Arcs").
Direction tangent(int64_t px, int64_t py, Turn turn) {
  if (!in_range(px) || !in_range(py)) {
    return make(DirectionKind::OutOfRange);
  }
  if (px == 0 && py == 0) {
    return make(DirectionKind::None);
  }
  if (turn == Turn::Cw) {
    return Direction{py, -px, DirectionKind::Xy};
  }
  return Direction{-py, px, DirectionKind::Xy};
}

// |components| <= 2^31 - 1: each product < 2^62, the sum or difference < 2^63.
constexpr int64_t cross(const Direction& a, const Direction& b) { return a.x * b.y - a.y * b.x; }
constexpr int64_t dot(const Direction& a, const Direction& b) { return a.x * b.x + a.y * b.y; }

using intmath::isqrt;  // floor(sqrt(n)) for any uint64 (core/intmath)

struct UnitQ30 {
  int64_t x;  // [-2^30, 2^30], within 2 LSB of the real unit vector * 2^30
  int64_t y;
};

// Unit vector of an Xy direction in Q30. The vector is first scaled by 2^s (exact, the same
// direction) until its larger |component| is in [2^30, 2^31), so the length L is >= 2^30 and
// its floor costs < 1 LSB; x'^2 + y'^2 < 2^63 and x' * 2^30 < 2^61 fit.
UnitQ30 unit_q30(const Direction& d) {
  const uint64_t ax = detail::magnitude(d.x);
  const uint64_t ay = detail::magnitude(d.y);
  uint64_t m = ax > ay ? ax : ay;  // [1, 2^31 - 1]
  int64_t scale = 1;
  while (m < (uint64_t{1} << 30)) {
    m <<= 1;
    scale *= 2;
  }
  const int64_t x = d.x * scale;
  const int64_t y = d.y * scale;
  const uint64_t sum = static_cast<uint64_t>(x * x) + static_cast<uint64_t>(y * y);
  const auto len = static_cast<int64_t>(isqrt(sum));  // [2^30, 2^31.5)
  constexpr int64_t kQ30 = int64_t{1} << 30;
  return UnitQ30{x * kQ30 / len, y * kQ30 / len};
}

constexpr int64_t abs64(int64_t v) { return v < 0 ? -v : v; }

}  // namespace

Direction line_direction(int64_t dx, int64_t dy, int64_t dz) {
  if (!in_range(dx) || !in_range(dy)) {
    return make(DirectionKind::OutOfRange);
  }
  if (dx == 0 && dy == 0) {
    return make(dz != 0 ? DirectionKind::ZOnly : DirectionKind::None);
  }
  return Direction{dx, dy, DirectionKind::Xy};
}

Direction arc_start_direction(int64_t sx, int64_t sy, Turn turn) { return tangent(sx, sy, turn); }

Direction arc_end_direction(int64_t ex, int64_t ey, Turn turn) { return tangent(ex, ey, turn); }

uint16_t speed_factor_permille(int32_t turn_mdeg) {
  if (turn_mdeg == 0) {
    return 1000;
  }
  if (turn_mdeg < 0 || turn_mdeg >= 90'000) {
    return 0;  // negative or > 180000: not a turn; >= 90 deg: full stop [T, seed-003.md §6]
  }
  // 1000 * (90000 - t) + 45000 <= 90'045'000: int32; half up.
  const int32_t f = (1000 * (90'000 - turn_mdeg) + 45'000) / 90'000;
  return static_cast<uint16_t>(f > 999 ? 999 : f);
}

Junction junction(const Direction& in, const Direction& out) {
  const auto either = [&](DirectionKind k) { return in.kind == k || out.kind == k; };
  if (either(DirectionKind::OutOfRange)) {
    return Junction{0, 0, JunctionKind::Invalid};
  }
  if (either(DirectionKind::None)) {
    return Junction{0, 0, JunctionKind::NoDirection};
  }
  if (either(DirectionKind::ZOnly)) {
    return Junction{0, 0, JunctionKind::ZOnlyStop};
  }
  const int64_t c = cross(in, out);
  const int64_t d = dot(in, out);
  if (c == 0 && d > 0) {
    return Junction{0, 1000, JunctionKind::Straight};
  }
  // Not both zero (the vectors are non-zero), so the angle is defined; |c| < 2^63.
  int32_t turn = atan2_mdeg(abs64(c), d).mdeg;  // [0, 180000]
  if (turn == 0) {
    turn = 1;  // not parallel: never reported as a zero turn
  }
  if (d > 0) {
    return Junction{turn, speed_factor_permille(turn), JunctionKind::Corner};
  }
  return Junction{turn, 0, JunctionKind::Stop};
}

uint32_t junction_speed(uint32_t v_max, const Junction& j, const Direction& in, const Direction& out,
                        uint32_t v_jump) {
  if ((j.kind != JunctionKind::Straight && j.kind != JunctionKind::Corner) || j.factor_permille > 1000 ||
      !in.has_direction() || !out.has_direction()) {
    return 0;
  }
  const auto by_factor = static_cast<uint32_t>(uint64_t{v_max} * j.factor_permille / 1000);
  if (cross(in, out) == 0 && dot(in, out) > 0) {
    return by_factor;  // parallel: the velocity vector does not jump
  }
  const UnitQ30 a = unit_q30(in);
  const UnitQ30 b = unit_q30(out);
  const int64_t dux = abs64(b.x - a.x);
  const int64_t duy = abs64(b.y - a.y);
  // Each unit component is within 2 LSB, so |du| is within 4: +4 makes it an upper bound.
  const auto du_upper = static_cast<uint64_t>((dux > duy ? dux : duy) + 4);
  const uint64_t cap = (uint64_t{v_jump} << 30) / du_upper;
  return cap < by_factor ? static_cast<uint32_t>(cap) : by_factor;
}

}  // namespace ap::xy_lookahead
