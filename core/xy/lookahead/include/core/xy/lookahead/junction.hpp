// Corner look-ahead: the turn and the speed factor at the junction of two XY segments
// (seed-003.md §6 and §5.1, with the thesis code's defects a-e fixed; docs/lookahead.md).
//
// The thesis law [T, seed-003.md §6]: same direction -> factor 1; turn below 90 deg ->
// 1 - turn/90; above 90 deg -> 0 (full stop, the next segment starts from zero).
// Our fixes [D, docs/lookahead.md]:
//   (a) the turn comes from the exact integer cross and dot products of the two direction
//       vectors, turned into an angle by atan2_mdeg(|cross|, dot): no -atan quadrant error;
//   (b) that angle is the unsigned angle between the directions, already in [0, 180] deg:
//       no 170 vs -170 -> 340 wrap error;
//   (c) a Z-only segment has a typed direction (ZOnly) and a full stop on both sides; a
//       zero-length segment (None) is dropped by the caller (drop_segment), never an angle;
//   (e) arcs give their tangent at the junction point (arc_end_direction of the segment that
//       ends there, arc_start_direction of the one that starts there), not their first row.
// Integer only; ranges are written at each declaration.
#pragma once

#include <cstdint>

namespace ap::xy_lookahead {

// Largest |component| of a direction: cross and dot products of two directions are then
// below 2 * (2^31 - 1)^2 < 2^63 and fit int64. In steps at 20 steps/mm (seed-003.md §2.5)
// that is 107 km, far beyond any XY platform.
inline constexpr int64_t kComponentMax = 2'147'483'647;  // 2^31 - 1

enum class Turn : uint8_t { Cw, Ccw };  // G02, G03 (the lead maps its own enum onto this)

enum class DirectionKind : uint8_t {
  Xy,          // x, y is a non-zero vector along the motion in the XY plane
  ZOnly,       // no XY motion, Z moves: the XY axes stand still (full stop both sides)
  None,        // nothing moves (or an arc of radius 0): drop the segment (drop_segment)
  OutOfRange,  // a component beyond +-kComponentMax: a typed error, x = y = 0
};

struct Direction {
  int64_t x;  // [-kComponentMax, kComponentMax]; 0 unless kind == Xy
  int64_t y;  // [-kComponentMax, kComponentMax]; 0 unless kind == Xy
  DirectionKind kind;
  [[nodiscard]] constexpr bool has_direction() const { return kind == DirectionKind::Xy; }
};

// A straight move by (dx, dy, dz) steps. The direction is the XY projection (the look-ahead
// only judges the XY platform's axes); dz only decides ZOnly (XY zero, dz != 0) vs None (all
// zero). Any dz is accepted; |dx|, |dy| > kComponentMax -> OutOfRange.
[[nodiscard]] Direction line_direction(int64_t dx, int64_t dy, int64_t dz);

// Tangent of an arc at a point (sx, sy) / (ex, ey) given relative to the arc centre:
// CW (G02) tangent (y, -x), CCW (G03) tangent (-y, x). Radius 0 -> None; a component beyond
// +-kComponentMax -> OutOfRange.
[[nodiscard]] Direction arc_start_direction(int64_t sx, int64_t sy, Turn turn);
[[nodiscard]] Direction arc_end_direction(int64_t ex, int64_t ey, Turn turn);

// True for a segment along which nothing moves: the caller drops it and joins its neighbours
// directly (docs/lookahead.md "Zero-length moves").
[[nodiscard]] constexpr bool drop_segment(const Direction& d) { return d.kind == DirectionKind::None; }

enum class JunctionKind : uint8_t {
  Straight,     // exactly parallel, same sense (cross == 0, dot > 0): turn 0, factor 1000
  Corner,       // 0 < turn < 90 deg exactly (dot > 0, cross != 0): factor by the thesis law
  Stop,         // turn >= 90 deg exactly (dot <= 0): factor 0
  ZOnlyStop,    // one side is a Z-only move: factor 0
  NoDirection,  // one side is None (should have been dropped): factor 0
  Invalid,      // one side is OutOfRange: factor 0
};

struct Junction {
  int32_t turn_mdeg;         // [0, 180000] for Straight/Corner/Stop (0 iff Straight); 0 otherwise
  uint16_t factor_permille;  // [0, 1000]; 1000 iff Straight; <= 999 for Corner
  JunctionKind kind;
};

// The thesis law on a turn in mdeg [T, seed-003.md §6]: 1000 at 0; for 0 < t < 90000
// round-half-up(1000 * (90000 - t) / 90000) capped at 999 (so only an exactly straight
// junction runs at full speed); 0 for t >= 90000. t outside [0, 180000] is not a turn: 0.
[[nodiscard]] uint16_t speed_factor_permille(int32_t turn_mdeg);

// The junction between the end of segment `in` and the start of segment `out` (their
// directions at the junction point). Symmetric in (in, out) and invariant under scaling either
// vector and under rotating both by 90 deg (exact: it depends only on |cross| and dot).
// Turn error against the real angle <= 1 mdeg (0.6 from atan2_mdeg; a non-parallel turn that
// rounds to 0 is reported as 1).
[[nodiscard]] Junction junction(const Direction& in, const Direction& out);

// Junction speed, in the units of v_max and v_jump (e.g. steps/s) [D, docs/lookahead.md]:
//   min(floor(v_max * factor / 1000), the largest v whose per-axis velocity jump
//       v * |u_out - u_in| (u the unit directions, per component) is <= v_jump).
// j must be junction(in, out). Only Straight and Corner junctions with Xy directions have a
// speed; every other kind (and a factor > 1000) gives 0. Straight: no jump, v_max.
// The per-axis cap is conservative: cap * D < v_jump * 2^30 (never above the exact real value)
// and cap >= v_jump * 2^30 / (D + 8) - 1, D the exact max per-axis |u_out - u_in| in units of
// 2^-30 (unit vectors in Q30 are within 2 LSB; docs/lookahead.md derives the margin).
// Ranges: v_max, v_jump any uint32; intermediates v_jump * 2^30 < 2^62 in uint64.
[[nodiscard]] uint32_t junction_speed(uint32_t v_max, const Junction& j, const Direction& in, const Direction& out,
                                      uint32_t v_jump);

}  // namespace ap::xy_lookahead
