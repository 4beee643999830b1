// Reference models of the corner look-ahead (lookahead.hpp, docs/lookahead.md).
#include "models/xy/lookahead/lookahead.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ap::model::xy_lookahead {

double thesis_angle_deg(double ux, double uy) {
  // seed-003.md §6, verbatim order of the branches; pi as MATLAB's pi.
  const double pi = std::numbers::pi;
  double angle = 0;
  if (uy == 0 && ux > 0) {
    angle = 0;
  } else if (uy == 0 && ux < 0) {
    angle = 180;
  } else if (ux < 0) {
    angle = -(std::atan(uy / ux) * 180 / pi);
  } else {
    angle = std::atan(uy / ux) * 180 / pi;  // ux = uy = 0: atan(0/0) = NaN (defect c)
  }
  return angle;
}

double thesis_factor(double angle_prev_deg, double angle_deg) {
  const double angle_dif = std::abs(angle_deg - angle_prev_deg);
  if (angle_dif > 90) {
    return 0;
  }
  return 1 - angle_dif / 90;
}

double thesis_junction_factor(const ThesisSegment& prev, const ThesisSegment& next) {
  // interpolation{1,n}(1,3) - interpolation{1,n-1}(1,3): row 1 of both (defect e).
  const auto& p = prev.row_dirs.front();
  const auto& n = next.row_dirs.front();
  return thesis_factor(thesis_angle_deg(p.first, p.second), thesis_angle_deg(n.first, n.second));
}

double ref_angle_deg(double y, double x) { return std::atan2(y, x) * 180 / std::numbers::pi; }

double ref_turn_deg(double x1, double y1, double x2, double y2) {
  double d = ref_angle_deg(y2, x2) - ref_angle_deg(y1, x1);  // (-360, 360)
  d = std::fmod(std::abs(d), 360.0);
  return d > 180 ? 360 - d : d;
}

double ref_factor(double turn_deg) {
  if (turn_deg >= 90) {
    return 0;
  }
  return 1 - turn_deg / 90;
}

double ref_max_du(double x1, double y1, double x2, double y2) {
  const double l1 = std::hypot(x1, y1);
  const double l2 = std::hypot(x2, y2);
  return std::max(std::abs(x2 / l2 - x1 / l1), std::abs(y2 / l2 - y1 / l1));
}

}  // namespace ap::model::xy_lookahead
