// Reference models of the corner look-ahead (docs/lookahead.md). Floating point; never code
// under test.
//
// 1. The thesis model: the MATLAB code of seed-003.md §6 transcribed literally, defects kept:
//    (a) -atan(uy/ux) for ux < 0 (not atan2), (b) no wrap-around of the angle difference,
//    (c) NaN for ux = uy = 0, (d) ux = 0 -> atan(+-Inf) = +-90 (correct), (e) only row 1 of
//    each segment's interpolation matrix is compared.
// 2. The reference: std::atan2 directions, the unsigned turn wrapped into [0, 180] deg, the
//    thesis law on it, and the per-axis velocity-jump cap of junction_speed in real numbers.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace ap::model::xy_lookahead {

// ---- thesis model (seed-003.md §6, literal) -------------------------------------------------

// Column 3 of a row: the angle of the direction vector (ux, uy) = (k2 - k1) in degrees,
// exactly the thesis's if/elseif chain. Range: [-90, 90] or 180, or NaN for (0, 0).
[[nodiscard]] double thesis_angle_deg(double ux, double uy);

// Column 4: angle_dif = abs(angle - angle_prev); > 90 -> 0 else 1 - angle_dif/90 (no wrap;
// NaN in gives NaN out, since NaN > 90 is false).
[[nodiscard]] double thesis_factor(double angle_prev_deg, double angle_deg);

// A segment's interpolation matrix reduced to what the look-ahead reads: one direction
// vector per row (a line has the same vector on every row; an arc its tangent at each point).
struct ThesisSegment {
  std::vector<std::pair<double, double>> row_dirs;  // (ux, uy) per row, row 1 first
};

// The junction factor the thesis code assigns to segment `next` after `prev`: only row 1 of
// each is compared (defect e), i.e. prev's *start* direction, not its end.
[[nodiscard]] double thesis_junction_factor(const ThesisSegment& prev, const ThesisSegment& next);

// ---- correct reference --------------------------------------------------------------------

// std::atan2 in degrees, (-180, 180].
[[nodiscard]] double ref_angle_deg(double y, double x);
// Unsigned angle between two non-zero directions, in [0, 180] deg (wrap-around handled).
[[nodiscard]] double ref_turn_deg(double x1, double y1, double x2, double y2);
// The thesis law [T] on a correct turn: 1 at 0, 1 - t/90 below 90, 0 from 90.
[[nodiscard]] double ref_factor(double turn_deg);
// Max per-axis |u_out - u_in| (unit vectors).
[[nodiscard]] double ref_max_du(double x1, double y1, double x2, double y2);

}  // namespace ap::model::xy_lookahead
