#include "core/hc08/menu/menu.hpp"

#include "core/hc08/timer/timer.hpp"

namespace ap::hc08_menu {

std::array<std::uint8_t, 4> digits_of(std::uint16_t v) {
  if (v > 9999) v = 9999;
  return {static_cast<std::uint8_t>(v / 1000U), static_cast<std::uint8_t>(v / 100U % 10U),
          static_cast<std::uint8_t>(v / 10U % 10U), static_cast<std::uint8_t>(v % 10U)};
}

std::uint16_t value_of(const std::array<std::uint8_t, 4>& d) {
  std::uint16_t v = 0;
  for (const std::uint8_t x : d) v = static_cast<std::uint16_t>(v * 10U + (x % 10U));
  return v;
}

namespace {

// The basic states in the order LEFT/RIGHT walk them [T: SET_DIRECT's RIGHT goes to
// SET_SPEED, LEFT to SET_DRIVE]; the ends do not wrap [D].
State next_basic(State s, bool right) {
  const auto i = static_cast<std::uint8_t>(s);
  if (right) return i < static_cast<std::uint8_t>(State::Angle) ? static_cast<State>(i + 1U) : s;
  return i > 0 ? static_cast<State>(i - 1U) : s;
}

Action edit_digit(Menu& m, hc08_motor::Settings& set, Key k, bool speed) {
  if (m.digit > 3) m.digit = 0;  // a state no key makes
  switch (k) {
    case Key::Left: m.digit = m.digit > 0 ? static_cast<std::uint8_t>(m.digit - 1U) : 0; return Action::None;
    case Key::Right: m.digit = m.digit < 3 ? static_cast<std::uint8_t>(m.digit + 1U) : 3; return Action::None;
    // One digit up or down, 9 wraps to 0 and back, no carry into the next digit [D].
    case Key::Plus: m.edit[m.digit] = static_cast<std::uint8_t>((m.edit[m.digit] + 1U) % 10U); return Action::None;
    case Key::Minus: m.edit[m.digit] = static_cast<std::uint8_t>((m.edit[m.digit] + 9U) % 10U); return Action::None;
    case Key::Set: break;
  }
  // SET closes the editor: the number is checked against what the motor can do and adjusted
  // to the nearest speed it can make (002_*.txt:729: inputs "checked and, where needed,
  // adjusted", docs/hc08.md "Menu").
  const std::uint16_t v = value_of(m.edit);
  m.state = speed ? State::Speed : State::Angle;
  if (speed) {
    const hc08_timer::Fitted f = hc08_timer::fit_speed(v, set.drive);
    set.speed_centi = f.speed_centi;
    return f.adjust == hc08_timer::Adjust::None ? Action::SetSpeed : Action::SetSpeedAdjusted;
  }
  set.angle_deg = v;  // four digits: always within kAngleMax
  return Action::SetAngle;
}

}  // namespace

Action press(Menu& m, hc08_motor::Settings& set, Key k, bool running) {
  switch (m.state) {
    case State::SpeedDigit: return edit_digit(m, set, k, true);
    case State::AngleDigit: return edit_digit(m, set, k, false);
    default: break;
  }
  if (k == Key::Left || k == Key::Right) {
    m.state = next_basic(m.state, k == Key::Right);
    return Action::None;
  }
  const bool plus = k == Key::Plus;
  switch (m.state) {
    case State::Def:
      if (k == Key::Set) return Action::StartStop;
      if (running) return Action::None;  // the mode of a running motor stays [D]
      set.mode = plus ? hc08_motor::Mode::A : hc08_motor::Mode::B;
      return Action::SetMode;
    case State::Drive: {
      if (k == Key::Set || running) return Action::None;
      // The drive type changes; a set speed the new one cannot make (20.50 rev/s is 820 Hz in
      // full step, past its 800 Hz) is adjusted to the nearest it can (002_*.txt:729).
      set.drive = plus ? hc08_drive::Drive::Half : hc08_drive::Drive::Full;
      const hc08_timer::Fitted f = hc08_timer::fit_speed(set.speed_centi, set.drive);
      set.speed_centi = f.speed_centi;
      return f.adjust == hc08_timer::Adjust::None ? Action::SetDrive : Action::SetDriveAdjusted;
    }
    case State::Direction:
      if (k == Key::Set) return Action::None;
      set.right = plus;  // Revers = TRUE: right [T]
      return Action::SetDirection;
    case State::Speed:
    case State::Angle:
      if (k != Key::Set) return Action::None;  // [T: no parameter of its own]
      m.edit = digits_of(m.state == State::Speed ? set.speed_centi : set.angle_deg);
      m.digit = 0;
      m.state = m.state == State::Speed ? State::SpeedDigit : State::AngleDigit;
      return Action::None;
    case State::SpeedDigit:
    case State::AngleDigit: break;
  }
  return Action::None;
}

}  // namespace ap::hc08_menu
