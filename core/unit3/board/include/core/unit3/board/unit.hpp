#pragma once
// The 3-axis USB unit's firmware (seed 001; every decision in docs/unit3.md "The board"):
// bytes from the PC, the joystick, six endstops and six buttons in; STEP, DIR and MODE pins of
// three DRV8825 and replies to the PC out. The host drives it as the ATmega2560 would: one
// tick() per 1 ms main-loop pass, in which each axis's timer runs 250 clocks; receive() per
// byte from the UART; press() per button.
//
// Rules (docs/unit3.md "The board"):
//   - An axis runs for one source at a time: a PC move or the joystick. A move for a running
//     axis is refused (E20 busy); the stick is ignored on an axis a PC move runs.
//   - The stick drives only in the POSITIONS window; in the menu windows it reads as centred
//     (an axis it runs ramps down and stops). PC moves run in every window.
//   - Every move starts at entry 0 of the ramp table, climbs one entry per 10 ms and ends at
//     entry 0 on its exact count (the ramp-down the thesis lacks). The stick reverses or stops
//     an axis only from entry 0.
//   - An endstop stops its axis in the tick it is seen, without a ramp (the thesis's interrupt
//     [T §3.9]); motion away from it is allowed, a PC move towards it is refused (E23).
//   - D latches the direction of later moves; C zeroes the counters without stopping anything;
//     a new step mode reaches an axis when it is at rest (its MODE pins never change under a
//     running motor).
#include <array>
#include <cstdint>
#include <span>

#include "core/unit3/axis/counting.hpp"
#include "core/unit3/board/replies.hpp"
#include "core/unit3/menu/menu.hpp"
#include "core/unit3/ramp/ramp.hpp"
#include "core/unit3/settings/settings.hpp"
#include "protocol/unit3/wire/dialect.hpp"

namespace ap::unit3_board {

inline constexpr std::size_t kAxes = 3;
inline constexpr std::uint32_t kReportMs = 100;  // counter reports of running axes [D]

// The unit's own refusals, sent as E<code>; (the wire's line errors are codes 1..7).
enum class Refusal : std::uint8_t {
  Busy = 20,          // a move for an axis that is running
  NotMultiple = 21,   // not a whole number of pulses in the axis's step mode
  CounterRange = 22,  // would take the counter past +-(10^18 - 1)
  Endstop = 23,       // towards a closed endstop; also sent when one cuts a PC move short
};

// The name of a refusal code (busy, not_multiple, counter_range, endstop); nullptr for a code
// that is not one.
const char* refusal_key(std::uint8_t code);

// Endstop inputs, bit 2a = axis a's minimum end, bit 2a + 1 = its maximum end, 1 = switch
// closed [D]: the state of the switches, not the level of their pins (endstops_from_pins).
constexpr std::uint8_t endstop_bit(std::size_t axis, bool max_end) {
  return static_cast<std::uint8_t>(1U << (2U * axis + (max_end ? 1U : 0U)));
}
inline constexpr std::uint8_t kEndstopPins = 0x3F;  // the six inputs, bits 0..5 as endstop_bit

// The six endstop pins as the port reads them, in endstop_bit's order, to the switch state
// Inputs::endstops carries. The pins are active low: each has a 1 kΩ pull-up to 5 V and its
// switch pulls it to GND, log 0, when closed, wired as the buttons are
// (001_*.txt:845-853 and 858-866). So a high pin is an open switch; the port's two other bits are
// not endstops and are ignored. Whatever reads the port fills Inputs through this: in the
// harness, the simulated board (sim/unit3/src/board.cpp), which holds the six pin levels.
constexpr std::uint8_t endstops_from_pins(std::uint8_t pin_levels) {
  return static_cast<std::uint8_t>(~pin_levels & kEndstopPins);
}

struct Inputs {
  std::array<std::uint16_t, kAxes> adc{512, 512, 512};  // joystick, ADC0..2 -> X, Y, Z [D]
  std::uint8_t endstops = 0;  // closed switches (endstop_bit); endstops_from_pins of the port
};

enum class Source : std::uint8_t { Idle, Pc, Joystick };
const char* source_key(Source s);  // idle, pc, joystick

struct AxisState {
  Source source = Source::Idle;
  std::int8_t dir = 1;             // the DIR pin of the running motion: +1 towards the max end
  std::uint8_t entry = 0;          // the ramp table entry the timer runs at
  std::uint8_t mode = 0;           // the step mode the MODE pins show
  std::int64_t counter = 0;        // 1/32-step counts [T]
  std::uint64_t remaining = 0;     // pulses a PC move still sends
  std::uint32_t interval_ms = 0;   // ms into the current ramp interval
};

// What one tick put on the pins of one axis.
struct AxisOut {
  std::uint8_t pulses = 0;     // STEP pulses in this tick (0 or 1)
  std::uint16_t pulse_at = 0;  // timer clock of the pulse within the tick (1..250)
  std::int8_t dir = 1;
  unit3_axis::ModePins mode{};
  bool running = false;
};

class Unit {
 public:
  // Power-up (seed 001 §3.1): the settings from the EEPROM image (the defaults when it holds
  // none, docs/unit3.md "Settings"), counters 0, the POSITIONS window. The image is the
  // unit's EEPROM: the unit writes it when the settings are saved.
  explicit Unit(std::span<std::uint8_t, unit3_settings::kImageSize> eeprom);

  void receive(std::uint8_t byte);
  void press(unit3_menu::Button b);
  void tick(const Inputs& in);
  std::size_t take_tx(std::span<std::uint8_t> out) { return tx_.take(out); }

  // An index past the three axes reads axis X: never past the arrays.
  const AxisState& axis(std::size_t a) const { return axes_[a < kAxes ? a : 0]; }
  const AxisOut& out(std::size_t a) const { return out_[a < kAxes ? a : 0]; }
  const unit3_settings::Settings& settings() const { return settings_; }
  unit3_settings::Load loaded() const { return loaded_; }
  const unit3_menu::State& menu() const { return menu_; }
  std::uint64_t now_ms() const { return now_ms_; }
  std::uint32_t tx_dropped() const { return tx_.dropped(); }
  std::uint32_t eeprom_writes() const { return eeprom_writes_; }

 private:
  void execute(const unit3_wire::Command& c);
  void start_move(std::size_t a, std::uint64_t count);
  void run_axis(std::size_t a, const Inputs& in);
  void stop_axis(std::size_t a);
  void save_settings();
  void send_settings(const unit3_settings::Settings& s);
  void send_counter(std::size_t a);
  void send_error(std::uint8_t code);

  std::span<std::uint8_t, unit3_settings::kImageSize> eeprom_;
  unit3_settings::Settings settings_{};
  unit3_settings::Load loaded_ = unit3_settings::Load::Ok;
  unit3_menu::State menu_{};
  unit3_wire::Framer framer_{};
  Replies tx_{};
  std::array<AxisState, kAxes> axes_{};
  std::array<AxisOut, kAxes> out_{};
  std::array<unit3_ramp::Timer, kAxes> timers_{};
  std::array<std::int8_t, kAxes> dir_{1, 1, 1};  // latched by D; + after power-up [D]
  std::uint8_t endstops_ = 0;                     // as the last tick read them
  std::uint64_t now_ms_ = 0;
  std::uint32_t eeprom_writes_ = 0;
};

}  // namespace ap::unit3_board
