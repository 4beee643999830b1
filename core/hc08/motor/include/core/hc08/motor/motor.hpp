#pragma once
// The HC08 unit's motor (seed 002 §5.3, docs/hc08.md "Motor"): mode A turns at a speed until
// stopped, mode B turns by an angle. Driven by the timer's compare interrupt: each match
// switches the coils one step (on_match), and the motor says when the next match is due.
// Integer-only: positions in steps, angles in tenths of a degree, speeds in 0.01 rev/s.
#include <cstdint>

#include "core/hc08/drive/drive.hpp"
#include "core/hc08/timer/timer.hpp"

namespace ap::hc08_motor {

enum class Mode : std::uint8_t { A = 0, B = 1 };  // turn at a speed / turn by an angle [T]
inline constexpr std::uint16_t kAngleMax = 9999;   // four digits, degrees [T §4.2.3; whole turns allowed, D]

// The defaults are the power-up settings; the thesis names none of them (its MCon initial
// values were on its CD), each is a decision of docs/hc08.md "Power-up".
struct Settings {
  Mode mode = Mode::A;                                 // [D] the first mode of the assignment
  hc08_drive::Drive drive = hc08_drive::Drive::Full;  // [D] four-step, the larger holding torque [T Tab. 3.1]
  bool right = true;              // Revers = TRUE is "right" [T §5.2.5]; right = the table forwards [D]
  std::uint16_t speed_centi = 100;  // 1.00 rev/s [D]: 40 / 80 Hz, below both start frequencies
  std::uint16_t angle_deg = 90;     // [D] a whole number of steps in both drive types (10, 20)
};

enum class Error : std::uint8_t {
  None = 0,
  Busy,          // start while running
  BadSpeed,      // the timer cannot make it (hc08_timer::Error says why: see last_timer_error())
  AngleRange,    // more than four digits
};

class Motor {
 public:
  explicit Motor(hc08_drive::FullStep full = hc08_drive::FullStep::TwoPhase,
                 hc08_drive::PhaseOrder order = hc08_drive::PhaseOrder{});

  // Starts mode A or B with these settings; nothing changes on an error.
  Error start(const Settings& s);
  // Asks the motor to stop: it ramps down to the start frequency and stops there (mode A's
  // SET; in mode B it ends the move early and the next move counts from where it stopped).
  void stop();
  // Mode A while running: a new direction ramps down to the start frequency, reverses, and
  // ramps back up; a new speed ramps to it. Refused (false) when the speed cannot be made.
  void set_direction(bool right);
  bool set_speed(std::uint16_t speed_centi);
  // The drive type: only at rest (false otherwise).
  bool set_drive(hc08_drive::Drive d);

  // The timer's compare match: one step of the coils. Returns false when the motor was not
  // running (a stray interrupt: nothing moves).
  bool on_match();

  bool running() const { return running_; }
  // The timer program for the next period (valid while running).
  hc08_timer::Reload timer() const { return {hc08_timer::Error::None, ps_, tmod_}; }
  // BUSCLK ticks until the next match.
  std::uint32_t period_ticks() const { return (std::uint32_t{tmod_} + 1U) << ps_; }
  std::uint8_t port() const { return hc08_drive::port_byte(seq_.pattern(), order_); }
  std::uint8_t pattern() const { return seq_.pattern(); }
  hc08_drive::Drive drive() const { return seq_.drive(); }
  int dir() const { return right_ ? 1 : -1; }
  // The rotor's position in half steps (4.5°) since power-up, signed (right +): drive-independent.
  std::int64_t position_half() const { return half_; }
  // Steps of the current drive type since it was chosen.
  std::int64_t steps() const { return steps_; }
  // The rotor angle 0..3555 in tenths of a degree (the display's 0-360, docs/hc08.md).
  std::uint16_t angle_tenths() const;
  std::uint32_t remaining() const { return remaining_; }
  hc08_timer::Error last_timer_error() const { return timer_error_; }

 private:
  void program(const hc08_timer::Reload& r) {
    ps_ = r.ps;
    tmod_ = r.tmod;
  }
  bool at_or_below_start() const;

  hc08_drive::Sequencer seq_;
  hc08_drive::PhaseOrder order_;
  Mode mode_ = Mode::A;
  bool running_ = false;
  bool right_ = true;
  bool stopping_ = false;
  bool reverse_pending_ = false;
  std::uint8_t ps_ = 0;
  std::uint16_t tmod_ = 0;
  hc08_timer::Reload target_{};  // the set speed's reload
  std::uint32_t remaining_ = 0;  // mode B
  std::int64_t steps_ = 0;
  std::int64_t half_ = 0;
  // Mode B's commanded position in 1/360 half step (angle * 80, the rotor at half_ * 360): a move
  // goes to it in whole steps, rounded towards where it starts, and the rest is carried to the
  // next move, whatever the drive type: n moves never drift (docs/hc08.md "Mode B", "Angle
  // arithmetic").
  std::int64_t commanded_ = 0;
  // After a stop (mode A, or mode B early) the next move counts from where the rotor then is.
  bool from_rotor_ = false;
  hc08_timer::Error timer_error_ = hc08_timer::Error::None;
};

}  // namespace ap::hc08_motor
