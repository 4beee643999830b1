// Scenario files of the unit3 profile's end-to-end runs (docs/unit3-sim.md "Scenario language").
//
// The 3-axis USB unit (seed 001) speaks its own `;` dialect over a 19200-baud line, has a
// joystick, six endstops and six buttons; the first profile's language (docs/scenarios.md) names none of
// these, so this profile brings a small language of its own:
//
//   scenario NAME                      title "..."          duration 3 s
//   eeprom default|blank
//   at T send "D+++;Y000000000016000;" [lose N]     bytes the PC writes to the line
//   at T joystick x|y|z ADC            at T endstop x|y|z min|max on|off
//   at T press enter|back|up|down|left|right [xN]   at T power-cycle
//   expect [by T] report AXIS OP N|counter          the last counter report the PC has
//   expect [by T] replies "E20;" OP N  / reply "S" / no reply "S"
//   expect [by T] settings "M000;T444;"             expect [by T] no errors
//   expect at T|end QUANTITY AXIS OP N              the board's pins and state at T
//   expect between T1 and T2|end QUANTITY AXIS OP N the change of a quantity over [T1, T2]
//
// parse() checks the syntax, times, axes and ranges and names file:line on every error; the
// run (unit3.hpp) gives the semantics.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/scenario_text.hpp"

namespace ap::sim::unit3 {

using text::ParseError;

enum class Eeprom : std::uint8_t {
  Default,  // an image holding the default settings (full step, M6), as a written unit has
  Blank,    // all 0xFF, a unit never written: it loads the defaults and says Blank
};

enum class ActionKind : std::uint8_t { Send, Joystick, Endstop, Press, PowerCycle };

struct Action {
  std::int64_t t_us = 0;
  int line = 0;
  ActionKind kind = ActionKind::Send;
  std::string bytes;       // Send: the bytes the PC writes (after `lose`)
  std::uint8_t axis = 0;   // Joystick, Endstop: 0..2 = X, Y, Z
  std::uint16_t adc = 512; // Joystick
  bool max_end = false;    // Endstop
  bool on = false;         // Endstop: the switch closed
  std::string button;      // Press: enter back up down left right
  std::uint32_t times = 1; // Press: xN
};

using text::compare;
using text::Op;
using text::op_text;

// What an expectation judges. Report, Replies, Settings, NoErrors: the bytes the PC received
// by `t_us`. At: the board's quantity at `t_us`. Between: its change from `t0_us` to `t_us`.
enum class ExpectKind : std::uint8_t { Report, Replies, Settings, NoErrors, At, Between };

// The board quantities an At/Between expectation reads (docs/unit3-sim.md).
enum class Quantity : std::uint8_t { Pulses, Counter, Entry, Dir, Running, Remaining, Mode };
const char* quantity_name(Quantity q);

struct Expectation {
  int line = 0;
  std::string text;            // the line as written, for the report
  ExpectKind kind = ExpectKind::Report;
  std::int64_t t0_us = 0;      // Between: the start
  std::int64_t t_us = 0;       // by / at / the end of the window (the duration for `end`)
  std::uint8_t axis = 0;
  Quantity quantity = Quantity::Counter;
  Op op = Op::Eq;
  std::int64_t value = 0;
  bool value_is_counter = false;  // Report: compare with the unit's counter at t_us
  std::string bytes;              // Replies, Settings
};

struct Scenario {
  std::string file;
  std::string name;
  std::string title;
  std::int64_t duration_us = 0;
  Eeprom eeprom = Eeprom::Default;
  std::vector<Action> actions;            // in time order (stable: file order at one time)
  std::vector<Expectation> expectations;  // in file order
};

Scenario parse(const std::string& text, const std::string& file = "<scenario>");
Scenario parse_file(const std::string& path);

// "10 ms", "0.5 s", "250 us" -> microseconds; false on anything else.
bool parse_time(const std::string& number, const std::string& unit, std::int64_t& us);

}  // namespace ap::sim::unit3
