// Reference models of the thesis's interpolators (seed-003.md §3.1-§3.3), for the core/xy/interp
// tests (docs/interpolation.md). Doubles and Eigen are fine here: never code under test.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace ap::model::xy_dda {

// The thesis's DDA line (seed §3.1, the MATLAB loop with i = 0): steps = max |to - from|,
// increments (to - from) / steps added to a double accumulator, steps + 1 points, NOT rounded.
// A zero-length move returns the single point `from`: the thesis divides 0 by 0 (NaN,
// seed §11.6); this model does not.
std::vector<Eigen::Vector3d> line(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

// MATLAB round(): half away from zero ("rounded only when used", seed §3.1).
Eigen::Vector3i round_half_away(const Eigen::Vector3d& p);

// line() with every point rounded.
std::vector<Eigen::Vector3i> rounded_line(const Eigen::Vector3i& from, const Eigen::Vector3i& to);

// The thesis's all-octant Bresenham loop (seed §3.2, verbatim loop; the initialisation the
// extraction infers: dx = |x2-x1|, sx = sign, dy = -|y2-y1|, sy = sign, err = dx + dy).
std::vector<Eigen::Vector2i> thesis_bresenham(const Eigen::Vector2i& from, const Eigen::Vector2i& to);

// The thesis's two printed octant branches (seed §3.3, quadrant I, clockwise) from (0, r) to
// (r, 0), relative to the centre, with their double midpoint tests as printed. At most 4r + 4
// iterations (a guard; the thesis has none).
std::vector<Eigen::Vector2i> thesis_quadrant1_cw(int r);


// Angle of p about the origin measured in the turning direction from `start`, in [0, 2*pi).
double swept_angle(const Eigen::Vector2d& start, const Eigen::Vector2d& p, bool clockwise);

}  // namespace ap::model::xy_dda
