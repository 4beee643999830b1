#pragma once
// The HC08 unit's menu (seed 002 §4.2.3, Tab. 4.3, the SET_DIRECT code of §5.2.5; docs/hc08.md
// "Menu"): five basic states in a row, LEFT/RIGHT walk it, PLUS/MINUS set the state's
// parameter, SET starts or stops the motor in S_DEF and opens or closes digit editing of the
// speed and the angle (four digits, PLUS/MINUS add or take one from digit x).
// The thesis's automaton runs twice per key: the first pass changes the state, the second
// (with KB_NOCODE) "activates" it, i.e. draws it. Here press() is the first pass and returns
// what the unit must do; draw is always the second pass (the board redraws after every key).
#include <array>
#include <cstdint>

#include "core/hc08/motor/motor.hpp"

namespace ap::hc08_menu {

enum class Key : std::uint8_t { Set, Left, Right, Plus, Minus };  // KB_SET .. KB_MINUS [T Tab. 4.2]
inline constexpr std::uint8_t kKeys = 5;

enum class State : std::uint8_t {
  Def,         // S_DEF: the angle (mode A: K2, mode B: K3); SET starts / stops [T]
  Drive,       // SET_DRIVE: PLUS eight-step, MINUS four-step [T]
  Direction,   // SET_DIRECT: PLUS right, MINUS left [T]
  Speed,       // SET_SPEED
  Angle,       // SET_ANGLE
  SpeedDigit,  // SET_SPEEDx
  AngleDigit,  // SET_ANGLEx
};

struct Menu {
  State state = State::Def;  // the initial state [T]
  std::uint8_t digit = 0;    // x in SET_SPEEDx / SET_ANGLEx: 0 the leftmost of four
  std::array<std::uint8_t, 4> edit{};  // the number being edited, most significant digit first
};

enum class Action : std::uint8_t {
  None,
  StartStop,     // S_DEF + SET
  SetMode,       // S_DEF + PLUS / MINUS: settings.mode changed
  SetDrive,      // settings.drive changed
  SetDirection,  // settings.right changed
  SetSpeed,      // the edited speed accepted into settings.speed_centi
  SetAngle,      // the edited angle accepted into settings.angle_deg
  // The thesis checks the user's inputs and adjusts them to the motor (002_*.txt:729): a speed
  // the motor cannot make is set to the nearest it can (hc08_timer::fit_speed) and said so.
  SetSpeedAdjusted,  // the edited speed was outside the drive type's range: settings.speed_centi
                     // holds the nearest end of it instead
  SetDriveAdjusted,  // settings.drive changed, and the set speed, outside the new drive type's
                     // range (21.25 rev/s is 850 Hz in full step), is its nearest end now
};

// One key in the first pass. `settings` is the unit's; it changes only as the Action says.
// `running` tells whether the motor runs: the drive type is changed only at rest [D].
Action press(Menu& m, hc08_motor::Settings& settings, Key k, bool running);

// The four digits of a number 0..9999, and back.
std::array<std::uint8_t, 4> digits_of(std::uint16_t v);
std::uint16_t value_of(const std::array<std::uint8_t, 4>& d);

}  // namespace ap::hc08_menu
