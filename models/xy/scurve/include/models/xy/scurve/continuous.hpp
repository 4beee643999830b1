#pragma once
// The continuous 7-segment jerk-limited profile (seed-003.md §5.4, the standard supplement),
// in double precision and continuous time: the reference the core's whole-tick integer
// profile is compared with (docs/scurve.md "Reference model"). Never code under test.
#include <array>

namespace ap::model::xy_scurve {

struct ContinuousProfile {
  double jerk = 0;                 // J (units/s^3)
  std::array<double, 7> dur{};     // Tj, Ta-2Tj, Tj, Tv, Tj, Td-2Tj, Tj (s)
  double v_peak = 0;               // units/s
  double a_peak = 0;               // units/s^2
  double total = 0;                // s
  double length = 0;               // units
};

struct Sample {
  double j = 0, a = 0, v = 0, p = 0;
};

// Rest to rest over `length` with limits V, A, J (> 0), as in seed §5.4:
//   V J >= A^2: Tj = A/J, Ta = Tj + V/A; else Tj = sqrt(V/J), Ta = 2 Tj;
//   Tv = (L - 2 Sa)/V with Sa = V Ta/2; Tv < 0: reduced peak
//   L >= 2 A^3/J^2: v_p = (-A^2/J + sqrt(A^4/J^2 + 4 L A))/2, else v_p = (L^2 J/4)^(1/3).
ContinuousProfile continuous_plan(double length, double v_max, double a_max, double j_max);

// j, a, v, p at time t (s) by the closed forms (2-22)..(2-24) per segment; after the end: rest at L.
Sample continuous_at(const ContinuousProfile& p, double t);

}  // namespace ap::model::xy_scurve
