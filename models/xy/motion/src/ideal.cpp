#include "models/xy/motion/ideal.hpp"

#include <algorithm>
#include <cmath>

namespace ap::model::xy_motion {

Profile ideal_move(double distance, double v_start, double v_max, double accel) {
  Profile p;
  p.distance = distance;
  p.v_start = v_start;
  p.accel = accel;
  if (distance <= 0) {
    return p;
  }
  const double ramps = (v_max * v_max - v_start * v_start) / accel;  // both ramps together
  if (ramps <= distance) {
    p.v_peak = v_max;
    p.t_cruise = (distance - ramps) / v_max;
  } else {
    p.v_peak = std::sqrt(accel * distance + v_start * v_start);
    p.triangle = true;
  }
  p.t_ramp = (p.v_peak - v_start) / accel;
  p.t_total = 2 * p.t_ramp + p.t_cruise;
  return p;
}

double brake_time(double v, double v_start, double accel) { return v > v_start ? (v - v_start) / accel : 0; }

double brake_distance(double v, double v_start, double accel) {
  return v > v_start ? (v * v - v_start * v_start) / (2 * accel) : 0;
}

}  // namespace ap::model::xy_motion
