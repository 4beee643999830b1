// Reference model: the ideal continuous motion of one move from rest to rest.
// The speed jumps 0 -> v_start at t = 0, rises at `accel` to the peak, cruises, falls at
// `accel` to v_start and jumps to 0 exactly at the target. Trapezoid when the distance allows
// reaching v_max, otherwise a triangle with peak sqrt(accel * distance + v_start^2).
// Units are whatever the caller uses consistently (usteps, usteps/s, usteps/s^2 here).
#pragma once

namespace ap::model::xy_motion {

struct Profile {
  double distance = 0;   // >= 0
  double v_start = 0;
  double v_peak = 0;
  double accel = 0;
  double t_ramp = 0;     // duration of each ramp
  double t_cruise = 0;
  double t_total = 0;
  bool triangle = false;
};

// distance >= 0, 0 < v_start <= v_max, accel > 0.
[[nodiscard]] Profile ideal_move(double distance, double v_start, double v_max, double accel);

// Braking from v to v_start: time and distance (the continuous DD of Tab. 7-3).
[[nodiscard]] double brake_time(double v, double v_start, double accel);
[[nodiscard]] double brake_distance(double v, double v_start, double accel);

}  // namespace ap::model::xy_motion
