// Mode A and mode B over the timer and the sequencer (motor.hpp, docs/hc08.md "Motor").
#include "core/hc08/motor/motor.hpp"

namespace ap::hc08_motor {

namespace {

namespace t = hc08_timer;

// floor(a / b) for b > 0.
std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

Motor::Motor(hc08_drive::FullStep full, hc08_drive::PhaseOrder order)
    : seq_(hc08_drive::Drive::Full, full), order_(order) {}

bool Motor::at_or_below_start() const {
  return ps_ > 0 || tmod_ >= t::tmod_at_hz(t::start_hz(seq_.drive()));
}

Error Motor::start(const Settings& s) {
  if (running_) return Error::Busy;
  if (s.mode == Mode::B && s.angle_deg > kAngleMax) return Error::AngleRange;
  const t::Reload r = t::reload(s.speed_centi, s.drive);
  if (r.error != t::Error::None) {
    timer_error_ = r.error;
    return Error::BadSpeed;
  }
  timer_error_ = t::Error::None;
  set_drive(s.drive);
  mode_ = s.mode;
  right_ = s.right;
  target_ = r;
  stopping_ = false;
  reverse_pending_ = false;
  if (mode_ == Mode::B) {
    // The commanded position and the rotor in one unit for both drive types, 1/360 half step
    // (1/80 degree): what a move cannot turn is carried to the next one, across a change of
    // drive type too (docs/hc08.md "Angle arithmetic"). A move stopped early or a mode A run
    // leaves no debt: the next move counts from where the rotor is (a drive change included).
    if (from_rotor_) commanded_ = half_ * 360;
    from_rotor_ = false;
    const std::int64_t dir = right_ ? 1 : -1;
    commanded_ += dir * static_cast<std::int64_t>(s.angle_deg) * 80;
    // Whole steps towards it, rounded towards where the move starts (never past it), and none
    // against the move's own direction (a carried remainder may lie behind the rotor).
    const std::int64_t unit = s.drive == hc08_drive::Drive::Full ? 720 : 360;
    const std::int64_t n = floor_div(dir * (commanded_ - half_ * 360), unit);
    remaining_ = static_cast<std::uint32_t>(n > 0 ? n : 0);  // <= (720 + 9999 * 80) / 360
    if (remaining_ == 0) return Error::None;                 // under a step: carried
  }
  // Above the start frequency the motor starts at it and ramps; at or below, at its speed.
  const std::uint16_t start_tmod = t::tmod_at_hz(t::start_hz(s.drive));
  program(r.ps == 0 && r.tmod < start_tmod ? t::Reload{t::Error::None, 0, start_tmod} : r);
  running_ = true;
  return Error::None;
}

void Motor::stop() {
  if (running_) stopping_ = true;
}

void Motor::set_direction(bool right) {
  if (!running_) {
    right_ = right;
    return;
  }
  if (mode_ == Mode::A) reverse_pending_ = right != right_;
}

bool Motor::set_speed(std::uint16_t speed_centi) {
  const t::Reload r = t::reload(speed_centi, seq_.drive());
  if (r.error != t::Error::None) {
    timer_error_ = r.error;
    return false;
  }
  target_ = r;
  return true;
}

bool Motor::set_drive(hc08_drive::Drive d) {
  if (running_) return false;
  if (d == seq_.drive()) return true;
  half_ += seq_.set_drive(d);
  steps_ = 0;
  return true;
}

bool Motor::on_match() {
  if (!running_) return false;
  seq_.step(dir());
  steps_ += dir();
  half_ += dir() * (seq_.drive() == hc08_drive::Drive::Full ? 2 : 1);
  if (mode_ == Mode::B && --remaining_ == 0) {
    running_ = false;
    return true;
  }
  if (at_or_below_start()) {
    if (stopping_) {
      running_ = false;
      remaining_ = 0;
      from_rotor_ = true;  // mode A, or mode B stopped early: no debt
      return true;
    }
    if (reverse_pending_) {
      // Reversed at or below the start frequency. The first step the other way is a start
      // from rest: it keeps this period (at or below the start frequency), and the ramp climbs
      // again from the step after it.
      right_ = !right_;
      reverse_pending_ = false;
      return true;
    }
  }
  const std::uint16_t start_tmod = t::tmod_at_hz(t::start_hz(seq_.drive()));
  const bool fast_now = ps_ == 0 && tmod_ < start_tmod;
  const bool fast_target = target_.ps == 0 && target_.tmod < start_tmod;
  if (!fast_target) {
    // A speed at or below the start frequency: down to the start frequency first, then at it.
    program(fast_now ? t::Reload{t::Error::None, 0, t::ramp_step(tmod_, start_tmod, true, seq_.drive())} : target_);
    return true;
  }
  const std::uint16_t now = fast_now ? tmod_ : start_tmod;
  std::uint16_t next = t::ramp_step(now, target_.tmod, stopping_ || reverse_pending_, seq_.drive());
  if (mode_ == Mode::B) {
    // The period programmed now is the next step's; the ramp then needs steps_to_start(next)
    // more to be back at the start frequency, so the last of the remaining steps is at it only
    // if remaining >= 1 + steps_to_start(next). The fastest of up, hold, down that keeps this
    // (down always does, by the same count one step earlier: docs/hc08.md "Ramp").
    const auto keeps = [&](std::uint16_t p) { return remaining_ >= 1U + t::steps_to_start(p, seq_.drive()); };
    if (!keeps(next)) next = keeps(now) ? now : t::ramp_step(now, target_.tmod, true, seq_.drive());
  }
  program({t::Error::None, 0, next});
  return true;
}

std::uint16_t Motor::angle_tenths() const {
  const std::int64_t pos = half_ % 80;  // 80 half steps per turn [T Tab. 3.1]
  return static_cast<std::uint16_t>((pos < 0 ? pos + 80 : pos) * 45);
}

}  // namespace ap::hc08_motor
