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

double speed_at(const Profile& p, double t) {
  if (t < 0 || t >= p.t_total) {
    return 0;
  }
  if (t < p.t_ramp) {
    return p.v_start + p.accel * t;
  }
  if (t < p.t_ramp + p.t_cruise) {
    return p.v_peak;
  }
  return p.v_peak - p.accel * (t - p.t_ramp - p.t_cruise);
}

double position_at(const Profile& p, double t) {
  if (t <= 0) {
    return 0;
  }
  if (t >= p.t_total) {
    return p.distance;
  }
  const double d_ramp = (p.v_start + p.v_peak) / 2 * p.t_ramp;
  if (t < p.t_ramp) {
    return p.v_start * t + p.accel * t * t / 2;
  }
  if (t < p.t_ramp + p.t_cruise) {
    return d_ramp + p.v_peak * (t - p.t_ramp);
  }
  const double u = t - p.t_ramp - p.t_cruise;
  return std::min(p.distance, d_ramp + p.v_peak * p.t_cruise + p.v_peak * u - p.accel * u * u / 2);
}

double brake_time(double v, double v_start, double accel) { return v > v_start ? (v - v_start) / accel : 0; }

double brake_distance(double v, double v_start, double accel) {
  return v > v_start ? (v * v - v_start * v_start) / (2 * accel) : 0;
}

}  // namespace ap::model::xy_motion
