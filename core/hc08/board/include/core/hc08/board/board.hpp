#pragma once
// The HC08 unit's firmware (seed 002 §5.2, docs/hc08.md "The board"): the keypad interrupt
// pushes debounced keys, the timer interrupt steps the motor and pushes its angle, the main
// loop pops messages in order and runs the menu (twice per key: change, then draw) and the
// display. The host drives it as the MC68HC908LJ12 would: key_sample() once per millisecond,
// timer_match() when the timer's period has run out (period_ticks() of BUSCLK), main_loop()
// in between.
#include <array>
#include <cstdint>

#include "core/hc08/board/keypad.hpp"
#include "core/hc08/board/queue.hpp"
#include "core/hc08/menu/menu.hpp"
#include "core/hc08/motor/motor.hpp"

namespace ap::hc08_board {

// What the LCD shows [T §4.3]: the state indicator X1..X6, K2 (mode A) or K3 (mode B), digit 5
// the direction, digit 8 the drive type, digits 1-4 a number with its decimal point.
struct Display {
  std::uint8_t indicator = 1;     // X1..X5 the basic states, X6 digit editing
  bool k2 = true, k3 = false;     // mode A / mode B
  char direction = 'r';           // 'r' right, 'l' left [D: the glyphs are not in the text]
  char drive = '4';               // '4' four-step, '8' eight-step [D]
  std::uint16_t value = 0;        // digits 1-4
  std::uint8_t point = 0;         // digits after the decimal point: speed 2, angle in tenths 1, angle 0
  bool error = false;             // the last SET could not start the motor [D]; the menu sets
                                  // only speeds it can make, so this stays off in use
  bool adjusted = false;          // the last key adjusted the set speed into the motor's range
                                  // (002_*.txt:729; until the next key) [D]
  friend constexpr bool operator==(const Display&, const Display&) = default;
};

class Board {
 public:
  explicit Board(hc08_drive::FullStep full = hc08_drive::FullStep::TwoPhase,
                 hc08_drive::PhaseOrder order = hc08_drive::PhaseOrder{});

  // The keypad scan once per millisecond (the code KBI_Keypressed would read, 0 for none).
  void key_sample(std::uint8_t code);
  // A debounced key as the keypad interrupt pushes it (what key_sample does on a stable press).
  void push_key(std::uint8_t code);
  // The TIM1 compare interrupt: one step and a motor message. False if the timer was stopped.
  bool timer_match();
  bool timer_running() const { return motor_.running(); }
  std::uint32_t period_ticks() const { return motor_.period_ticks(); }
  // The main loop: every waiting message, in order.
  void main_loop();

  std::uint8_t port() const { return motor_.port(); }
  const Display& display() const { return display_; }
  const hc08_motor::Settings& settings() const { return settings_; }
  const hc08_menu::Menu& menu() const { return menu_; }
  const hc08_motor::Motor& motor() const { return motor_; }
  const Queue& queue() const { return queue_; }
  std::uint32_t unknown_keys() const { return unknown_keys_; }

 private:
  void on_key(std::uint8_t code);
  void draw();

  hc08_motor::Settings settings_{};
  hc08_menu::Menu menu_{};
  hc08_motor::Motor motor_;
  Queue queue_{};
  Debouncer debounce_{};
  Display display_{};
  std::uint16_t shown_angle_ = 0;  // the last angle a motor message brought
  std::uint32_t unknown_keys_ = 0;
};

}  // namespace ap::hc08_board
