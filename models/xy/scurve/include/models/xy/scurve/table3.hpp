#pragma once
// The thesis's Tab. 3 "Tabulka pro aproximaci S-krivky" (seed-003.md §5.2): its biased
// recurrence (A_n = A_{n-1} + J; V_n = V_{n-1} + A_n + J/2; P_n = P_{n-1} + V_n + A_n/2 + J/6,
// J = 0.2, dt = 1, each update using the already-updated values), computed EXACTLY in units
// of 1/30 and formatted as the thesis prints it; beside it the exact constant-jerk values
// (A = 0.2 n, V = 0.1 n^2, P = 0.2 n^3 / 6) produced by running the CORE's integrator
// (core/xy/scurve/integrator.hpp advance()), not a closed form. docs/scurve.md "Tab. 3".
#include <cstdint>
#include <string>
#include <vector>

namespace ap::model::xy_scurve {

struct Table3Row {
  int n = 0;
  // The thesis's recurrence, exact, in units of 1/30.
  int64_t a30 = 0, v30 = 0, p30 = 0;
  // As the thesis prints them (decimal comma).
  std::string jerk, accel, velocity, position, rounded;
  // The core's exact integrator in its normalised units (jerk u = 0.2): A = 0.2 a, V = 0.1 v2,
  // P = 0.2 p6 / 6 = p6 / 30.
  int64_t exact_a = 0, exact_v2 = 0, exact_p6 = 0;
  std::string exact_accel, exact_velocity, exact_position;  // accel as the thesis, v 1 decimal, p 4 decimals
};

// Rows 0..last (the thesis prints 0..15).
std::vector<Table3Row> table3_rows(int last = 15);

// The full text `axisproof gcode --table3` prints.
std::string table3_report();

}  // namespace ap::model::xy_scurve
