// Mechanical model of one axis: a lead screw integrated in the rotor of the Tab. 4-1 stepper,
// driving a carriage on a linear guide (seed 000 §2, eq. 4-1 .. 4-6). Reference model for
// tests and the simulated board; docs/mechanics.md gives the equations, the torque model and
// every assumed value (the thesis gives no lead, masses or friction).
//
// SI units throughout: m, s, kg, N*m, rad.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ap::model::xy_mechanics {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kG = 9.81;

// Tab. 4-1 (the chosen stepper) plus the driver supply, which the thesis does not give.
struct Motor {
  double step_angle_deg = 1.8;      // full step
  double holding_torque = 0.560;    // N*m at nominal current, both phases on
  double detent_torque = 0.024;     // N*m, unpowered
  double rotor_inertia = 82e-7;     // kg*m^2 (82 g*cm^2)
  double nominal_current = 1.7;     // A per phase
  double resistance = 1.8;          // ohm per phase
  double inductance = 3.8e-3;       // H per phase
  double supply_voltage = 12.0;     // V at the driver (ASSUMED: battery-powered board)
  double torque_derating = 0.7;     // ASSUMED: usable fraction of the holding torque when running
                                    // (pull-out below the corner speed; microstepping, ripple)

  [[nodiscard]] double full_steps_per_rev() const { return 360.0 / step_angle_deg; }
  // Rotor teeth = electrical cycles per mechanical revolution (50 for a 1.8 deg hybrid).
  [[nodiscard]] double rotor_teeth() const { return full_steps_per_rev() / 4.0; }
};

// Lead screw, carriage and guide (all ASSUMED defaults; see docs/mechanics.md).
struct Axis {
  double lead = 0.002;              // s: screw lead [m/rev]
  double mass = 5.0;                // m: platform + object (+ Y axis for X) [kg]
  double friction = 0.1;            // f1: guide friction coefficient
  double screw_inertia = 9.5e-7;    // kg*m^2 (steel screw d = 8 mm, 300 mm long)
  double efficiency = 1.0;          // screw efficiency; 1.0 = the thesis' eq. (4-6) as written
  std::uint32_t microsteps = 16;    // TMC2130 MRES setting
};

struct Params {
  Motor motor;
  Axis axis;
  // Required/available above this ratio is flagged as a lost-step risk; below it but above
  // warn_ratio as a warning (a margin for everything the model ignores).
  double risk_ratio = 1.0;
  double warn_ratio = 0.5;
  // Kinematics: x(t) is fitted by a local quadratic over steps within +-window/2 of each step
  // (at least 2 neighbours each side); the rotor and load filter the per-step speed jitter of
  // a tick-quantised ramp, so torque follows the low-frequency acceleration.
  double fit_window = 0.010;        // s
  // A gap between steps longer than this (or a direction change) ends a motion segment: the
  // axis is at rest; a segment starts and stops within one microstep (docs/mechanics.md).
  double rest_gap = 0.050;          // s
  // A segment starts (stops) by reaching (leaving) its first (last) step speed within this
  // many full steps: the rotor may lag the field by less than that without losing sync.
  double start_distance_fullsteps = 1.0;
};

// ---- equations (4-1) .. (4-6), one function each -------------------------------------------
double omega_from_speed(double v, double lead);                                   // (4-1)
double epsilon_from_accel(double a, double lead);                                 // (4-2)
double reduced_mass(double m, double inertia_sum, double lead);                   // (4-3)
double reduced_force(double torque, double lead, double m, double f1);            // (4-4)
double accel_from_torque(double torque, double lead, double m, double f1, double inertia_sum);  // (4-5)
double required_torque(double a, double lead, double m, double f1, double inertia_sum);        // (4-6)

// Everything the axis needs, from Params: inertia sum, step length, torque at a speed.
class Model {
 public:
  explicit Model(Params p = {});
  [[nodiscard]] const Params& params() const { return p_; }
  [[nodiscard]] double inertia_sum() const;          // rotor + screw
  [[nodiscard]] double steps_per_rev() const;        // microsteps per revolution
  [[nodiscard]] double step_length() const;          // m per microstep
  // Torque the motor needs for acceleration a (signed, m/s^2) while moving in direction
  // dir (+1/-1); friction always opposes motion; divided by the screw efficiency.
  [[nodiscard]] double torque_required(double a, int dir) const;
  // Pull-out torque available at carriage speed v (m/s), see docs/mechanics.md:
  // T(w) = derating * T_hold * min(1, V / (I_nom * sqrt(R^2 + (N_r * w * L)^2))).
  [[nodiscard]] double torque_available(double v) const;
  // Speed above which the chopper can no longer hold nominal current (the curve's corner).
  [[nodiscard]] double corner_speed() const;

 private:
  Params p_;
};

// One microstep on the STEP line (rising edge time) and the DIR level it was taken with.
struct Step {
  double t;   // s
  int dir;    // +1 or -1
};

enum class Risk : std::uint8_t { none, warning, lost_step };

struct Sample {
  double t;            // s
  double x;            // m, carriage position after this step (0 = position before the first step)
  double v;            // m/s (signed)
  double a;            // m/s^2 (signed)
  double torque_required;   // N*m, magnitude
  double torque_available;  // N*m
  Risk risk;
};

struct Summary {
  std::size_t steps = 0;
  std::size_t segments = 0;
  double max_speed = 0.0;            // |v|, m/s
  double max_accel = 0.0;            // |a|, m/s^2
  double max_torque_required = 0.0;  // N*m
  double min_margin = 0.0;           // min of available / required over all samples
  std::size_t warnings = 0;
  std::size_t lost_step_risks = 0;
  std::optional<double> first_risk_t;   // s, first lost-step risk
};

struct Result {
  std::vector<Sample> samples;   // one per step, plus a start and a stop sample per segment
  Summary summary;
};

// Steps must be in non-decreasing time order; throws std::invalid_argument otherwise.
Result simulate(const Model& model, std::span<const Step> steps);

// Incremental form of simulate() for a simulated board that produces steps as virtual time runs:
// feed steps in order; flush(now) returns the samples of every motion segment that has ended
// (a DIR change, or no step for more than rest_gap before `now`). Segments are independent in
// simulate(), so the samples are exactly those simulate() gives for the whole run; x continues
// across flushes. finish() returns the rest.
class Tracker {
 public:
  explicit Tracker(Model model) : model_(std::move(model)) {}
  void step(double t, int dir);                    // throws std::invalid_argument like simulate()
  std::vector<Sample> flush(double now);
  std::vector<Sample> finish();
  [[nodiscard]] const Summary& summary() const { return summary_; }   // over flushed samples
  [[nodiscard]] double position() const { return position_; }         // after the last step fed

 private:
  std::vector<Sample> take(std::size_t n);
  Model model_;
  std::vector<Step> pending_;
  double flushed_x_ = 0.0;    // carriage position at the start of pending_
  double position_ = 0.0;
  Summary summary_{};
  bool any_margin_ = false;
};

// Step times of a trapezoidal (or triangular) move of `distance` metres from rest to rest,
// starting at t0 with start speed v_start, cruise speed v_max and acceleration a (ideal, not
// tick-quantised): the reference profile of tests and of docs/mechanics.md.
std::vector<Step> trapezoid_steps(const Model& model, double distance, double v_start, double v_max,
                                  double a, double t0 = 0.0);

std::string to_string(Risk r);

}  // namespace ap::model::xy_mechanics
