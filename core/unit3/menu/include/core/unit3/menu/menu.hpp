#pragma once
// The unit's windows and six buttons (seed 001 §3.7, docs/unit3.md "The menu"):
//   POSITIONS --Enter--> MENU --Enter on an item--> STEP SIZE | THREAD TYPE | (zero positions)
//   STEP SIZE, THREAD TYPE --Back--> MENU (the settings are saved and sent to the PC)
//   MENU --Back--> POSITIONS
// A pure state machine over the unit's settings: it changes them in place and says what the
// unit has to do (zero the counters, save and send the settings); it never touches a motor.
#include <cstdint>

#include "core/unit3/settings/settings.hpp"

namespace ap::unit3_menu {

enum class Button : std::uint8_t { Enter, Back, Up, Down, Left, Right };
inline constexpr std::uint8_t kButtons = 6;

enum class Window : std::uint8_t { Positions, Menu, StepSize, Thread };
// The menu's items in the thesis's order [T §3.7].
enum class Item : std::uint8_t { StepSize = 0, Thread = 1, Zero = 2 };
inline constexpr std::uint8_t kItems = 3;

struct State {
  Window window = Window::Positions;  // after power-up [T]
  Item item = Item::StepSize;         // the highlighted menu item
  std::uint8_t axis = 0;              // the axis selected in STEP SIZE / THREAD TYPE (X, Y, Z)
  friend constexpr bool operator==(const State&, const State&) = default;
};

enum class Effect : std::uint8_t {
  None,
  Zero,  // zero the three counters [T: the menu's "zero positions" item]
  Save,  // write the settings to the EEPROM and send them to the PC [T: Back from the windows]
};

// One button press. Lists and values saturate at their ends rather than wrap [D]. In STEP SIZE
// Left makes the step larger (mode - 1) and Right smaller (mode + 1) [T]; in THREAD TYPE
// Right goes to the next larger thread and Left back [D]. A change takes effect at once (the
// thesis's windows have no confirm); a moving axis keeps its step mode until it stops
// (docs/unit3.md "The board").
Effect press(State& s, unit3_settings::Settings& settings, Button b);

}  // namespace ap::unit3_menu
