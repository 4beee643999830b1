#include "models/xy/scurve/continuous.hpp"

#include <algorithm>
#include <cmath>

namespace ap::model::xy_scurve {

ContinuousProfile continuous_plan(double length, double v_max, double a_max, double j_max) {
  const double J = j_max, A = a_max, V = v_max, L = length;
  ContinuousProfile p;
  p.jerk = J;
  p.length = L;
  double tj = 0, ta = 0, vp = V;
  if (V * J >= A * A) {
    tj = A / J;
    ta = tj + V / A;
  } else {
    tj = std::sqrt(V / J);
    ta = 2 * tj;
  }
  const double sa = V * ta / 2;
  double tv = (L - 2 * sa) / V;
  if (tv < 0) {
    tv = 0;
    if (L >= 2 * A * A * A / (J * J)) {
      vp = (-A * A / J + std::sqrt(A * A * A * A / (J * J) + 4 * L * A)) / 2;
      tj = A / J;
      ta = tj + vp / A;
    } else {
      vp = std::cbrt(L * L * J / 4);
      tj = std::sqrt(vp / J);
      ta = 2 * tj;
    }
  }
  p.dur = {tj, ta - 2 * tj, tj, tv, tj, ta - 2 * tj, tj};
  p.v_peak = vp;
  p.a_peak = J * tj;
  p.total = 2 * ta + tv;
  return p;
}

Sample continuous_at(const ContinuousProfile& p, double t) {
  static constexpr std::array<double, 7> kJerk{+1, 0, -1, 0, -1, 0, +1};
  Sample s;
  for (std::size_t i = 0; i < 7; ++i) {
    const double d = p.dur[i];
    const double j = kJerk[i] * p.jerk;
    const double dt = std::clamp(t, 0.0, d);
    s.p += s.v * dt + s.a * dt * dt / 2 + j * dt * dt * dt / 6;
    s.v += s.a * dt + j * dt * dt / 2;
    s.a += j * dt;
    if (t < d) {
      s.j = j;
      return s;
    }
    t -= d;
  }
  s.j = 0;
  return s;
}

}  // namespace ap::model::xy_scurve
