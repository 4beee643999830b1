#pragma once
// The HC08 unit's angle arithmetic as the thesis and docs/hc08.md "Angle arithmetic" state it,
// for the angle oracle (properties/hc08/angle_oracle_test.cpp), the board's stateful test and
// the key fuzz target: where the rotor is after any signed number of steps of either drive
// type, what the display shows for it (left of the start included), what a mode B move turns,
// and what a change of drive type does to the position and to mode B's carried remainder.
// Written from the thesis (seed 002, `002_*.txt`) and the docs, without the unit's code; it
// shares nothing with core/hc08/motor or core/hc08_drive.
//
// Units. The rotor's position is a signed count of half steps (4.5 degrees) from power-up,
// right positive: one revolution is 80 half-step positions ("osmitaktní" 80 steps of 4.5°,
// "čtyřtaktní" 40 of 9°: 002_*.txt l. 462-463, Tab. 3.1), so both drive types' rest positions
// lie on this one grid and a full step is two of its points. Mode B's commanded position is
// kept in 1/360 of a half step (1/80 degree): any whole number of degrees is exact in it
// (a degrees = 80 a), a half step is 360 and a full step 720, whatever the drive type.
#include <cstdint>

namespace ap::model::hc08 {

inline constexpr std::int64_t kHalfStepsPerTurn = 80;  // 002_*.txt l. 462: 80 steps per turn in half step
inline constexpr int kTenthsPerHalfStep = 45;          // l. 463: 4.5° per half step, in 0.1°
inline constexpr std::int64_t kUnitsPerDegree = 80;    // commanded position: 1/80° = 1/360 half step
inline constexpr std::int64_t kUnitsPerHalfStep = 360;

// Half steps per step of a drive type: full step ("čtyřtaktní", l. 401) 2, half step
// ("osmitaktní", l. 411: "twice the angular resolution", l. 405) 1.
constexpr int half_steps_per_step(bool half) { return half ? 1 : 2; }

// Floor division and the non-negative modulo (a signed position left of the start must not be
// truncated towards zero: -1 half step is 355.5°, not -4.5° or 4.5°).
constexpr std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}
constexpr std::int64_t floor_mod(std::int64_t a, std::int64_t b) { return a - floor_div(a, b) * b; }

// The display's angle for a position (002_*.txt l. 768: in S_DEF digits 1-4 show "the current
// rotor angle (0-360°)"; CurAngle, "current rotation angle", is a signed int, l. 1063): the
// position modulo one turn, in tenths of a degree, 0 .. 3555 (docs/hc08.md "Display").
constexpr int display_tenths(std::int64_t half_steps) {
  return static_cast<int>(floor_mod(half_steps, kHalfStepsPerTurn)) * kTenthsPerHalfStep;
}

class AngleModel {
 public:
  std::int64_t position_half() const { return half_; }
  int angle_tenths() const { return display_tenths(half_); }
  bool half() const { return half_drive_; }
  // Mode B's commanded position (1/80°) once a move has been planned; meaningful while anchored.
  std::int64_t commanded() const { return commanded_; }

  // A change of drive type at rest (docs/hc08.md "Excitation"): to half step the rotor stays
  // (half step has every full-step pattern); to full step from a position full step lacks
  // (an odd half-step count: full-step positions are the even ones, power-up being one) it
  // moves half a step forward, +1. The commanded position is kept in degrees: the remainder a
  // mode B move could not turn is carried into the new drive type. Returns the half steps moved.
  int set_drive(bool half);

  // The rotor turned `steps` steps of the current drive type one way, outside a completed mode B
  // move (mode A runs): the next mode B move counts from where the rotor then is. Zero steps
  // moves nothing and changes nothing.
  void turned(bool right, std::int64_t steps);

  // Mode B (docs/hc08.md "Mode B", "Angle arithmetic"): a move by `angle_deg` degrees one way
  // adds it to the commanded position and turns the whole steps of the current drive type that
  // bring the rotor towards it without passing it, never against the move's own direction.
  // Returns that number of steps; finish_b() says how many the motor made.
  std::int64_t plan_b(bool right, int angle_deg);
  // The move ended after `done` steps (<= planned). All of them: the remainder stays commanded.
  // Fewer (stopped early by SET): no debt, the next move counts from where the rotor is.
  void finish_b(std::int64_t done);

 private:
  std::int64_t half_ = 0;       // rotor, half steps from power-up, right +
  bool half_drive_ = false;     // power-up: four-step (docs/hc08.md "Power-up")
  std::int64_t commanded_ = 0;  // 1/80 degree
  bool anchored_ = true;        // commanded_ is meaningful (power-up: the rotor at 0 = commanded 0)
  bool planned_right_ = true;
  std::int64_t planned_ = 0;
  std::int64_t planned_from_ = 0;
};

// The rotor's position read from the coils alone, as a bench with a logic analyser on PTA3..6
// would: each pattern is a rest position of the half-step table (docs/hc08.md "Excitation":
// phase 1..4 on PTA3..PTA6, 002_*.txt l. 676-688; the table 0x08 0x18 0x10 0x30 0x20 0x60
// 0x40 0x48 for the default phase order), and a change of pattern moves the rotor by the
// shortest way round the table: +-1 (half step), +-2 (full step). Fed every pattern the coils
// take (after every step and every drive change), it counts the rotor's half steps with no
// help from the unit's own counting. A jump of 3 or 4 positions, or a byte that is no rest
// position, cannot be followed: ok() turns false.
class CoilTracker {
 public:
  // The coils at power-up (docs/hc08.md "Power-up": 0x18, the position's zero).
  explicit CoilTracker(std::uint8_t power_up_port = 0x18);
  void feed(std::uint8_t port);
  std::int64_t position_half() const { return half_; }
  int angle_tenths() const { return display_tenths(half_); }
  bool ok() const { return ok_; }

 private:
  static int index_of(std::uint8_t port);
  int index_ = 0;
  std::int64_t half_ = 0;
  bool ok_ = true;
};

}  // namespace ap::model::hc08
