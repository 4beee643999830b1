#pragma once
// The BLE module's status pins (thesis Tab. 7-2) and the RGB LED (Tab. 7-4, §7.9.5), as pure
// functions of what the board samples, so the firmware drives the LED from the same state
// the tests see. The thesis gives the rows; what it leaves open (which row wins when two hold,
// blink periods) is decided in docs/board.md "LED (Tab. 7-4)".
#include <cstdint>

namespace ap::xy_board {

// Tab. 7-2, (STATUS1_IND, STATUS2_IND): (1,1) shutdown ("deep-sleep"), (1,0) standby
// (advertising, waiting for a connection), (0,0) connected (paired with the PC), (0,1) data
// session open.
enum class BleState : std::uint8_t { Shutdown, Standby, Connected, Session };

constexpr BleState ble_state(bool status1, bool status2) {
  if (status1) return status2 ? BleState::Shutdown : BleState::Standby;
  return status2 ? BleState::Session : BleState::Connected;
}

enum class LedColour : std::uint8_t { Off, Red, Green, Blue };
enum class LedBlink : std::uint8_t { Steady, Slow, Fast };

struct Led {
  LedColour colour = LedColour::Off;
  LedBlink blink = LedBlink::Steady;
  friend constexpr bool operator==(const Led&, const Led&) = default;
};

// Blink half-periods (docs/board.md "LED (Tab. 7-4)"): the thesis names slow and fast only.
inline constexpr std::uint32_t kLedSlowHalfPeriodMs = 500;
inline constexpr std::uint32_t kLedFastHalfPeriodMs = 125;

// Tab. 7-4's five rows, first match wins: low battery (red, fast), charger connected (red,
// steady), communicating with the PC (blue, steady), ready to pair (blue, slow), stand-by after
// power-on (green, steady). USB, faults and sleep have no row and no pattern of their own.
constexpr Led led_pattern(bool low_battery, bool charger, BleState ble) {
  if (low_battery) return {LedColour::Red, LedBlink::Fast};
  if (charger) return {LedColour::Red, LedBlink::Steady};
  if (ble == BleState::Session) return {LedColour::Blue, LedBlink::Steady};
  if (ble == BleState::Standby || ble == BleState::Connected) return {LedColour::Blue, LedBlink::Slow};
  return {LedColour::Green, LedBlink::Steady};
}

// Whether the LED is lit at `ms` since power-up (blinking starts lit).
constexpr bool led_lit(const Led& l, std::uint64_t ms) {
  if (l.colour == LedColour::Off) return false;
  switch (l.blink) {
    case LedBlink::Steady: return true;
    case LedBlink::Slow: return (ms / kLedSlowHalfPeriodMs) % 2 == 0;
    case LedBlink::Fast: return (ms / kLedFastHalfPeriodMs) % 2 == 0;
  }
  return true;
}

}  // namespace ap::xy_board
