#include "models/xy/dda/dda.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

namespace ap::model::xy_dda {

std::vector<Eigen::Vector3d> line(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d d = to - from;
  const double steps = d.cwiseAbs().maxCoeff();
  if (steps == 0.0) {
    return {from};  // seed §11.6: the thesis computes 0/0 here
  }
  const Eigen::Vector3d inc = d / steps;
  std::vector<Eigen::Vector3d> out;
  Eigen::Vector3d p = from;
  for (double i = 0; i <= steps; i += 1.0) {  // the thesis's `while i <= steps` with i = 0
    out.push_back(p);
    p += inc;
  }
  return out;
}

Eigen::Vector3i round_half_away(const Eigen::Vector3d& p) {
  Eigen::Vector3i r;
  for (int i = 0; i < 3; ++i) r[i] = static_cast<int>(std::round(p[i]));  // std::round: half away from zero
  return r;
}

std::vector<Eigen::Vector3i> rounded_line(const Eigen::Vector3i& from, const Eigen::Vector3i& to) {
  std::vector<Eigen::Vector3i> out;
  for (const auto& p : line(from.cast<double>(), to.cast<double>())) out.push_back(round_half_away(p));
  return out;
}

std::vector<Eigen::Vector2i> thesis_bresenham(const Eigen::Vector2i& from, const Eigen::Vector2i& to) {
  int x1 = from.x(), y1 = from.y();
  const int x2 = to.x(), y2 = to.y();
  const int dx = std::abs(x2 - x1), sx = x1 < x2 ? 1 : -1;
  const int dy = -std::abs(y2 - y1), sy = y1 < y2 ? 1 : -1;
  int err = dx + dy;
  std::vector<Eigen::Vector2i> out;
  while (true) {
    out.emplace_back(x1, y1);
    if (x2 == x1 && y2 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x1 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y1 += sy;
    }
  }
  return out;
}

std::vector<Eigen::Vector2i> thesis_quadrant1_cw(int r) {
  int x = 0, y = r;
  std::vector<Eigen::Vector2i> out{{x, y}};
  for (int guard = 0; (x != r || y != 0) && guard < 4 * r + 4; ++guard) {
    if (!(x >= 0 && y > 0)) break;  // left quadrant I: the elided branches would take over
    const double xd = x, yd = y, rd = r;
    if (std::abs(x) >= std::abs(y)) {  // the thesis's "1. oktant"
      if ((xd + 0.5) * (xd + 0.5) + (yd - 1) * (yd - 1) - rd * rd < 0) ++x;
      --y;
    } else {  // "2. oktant"
      if ((xd + 1) * (xd + 1) + (yd - 0.5) * (yd - 0.5) - rd * rd > 0) --y;
      ++x;
    }
    out.emplace_back(x, y);
  }
  return out;
}

double swept_angle(const Eigen::Vector2d& start, const Eigen::Vector2d& p, bool clockwise) {
  double a = std::atan2(p.y(), p.x()) - std::atan2(start.y(), start.x());
  if (clockwise) a = -a;
  const double two_pi = 2 * std::numbers::pi;
  while (a < 0) a += two_pi;
  while (a >= two_pi) a -= two_pi;
  return a;
}

}  // namespace ap::model::xy_dda
