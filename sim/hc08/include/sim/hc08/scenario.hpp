// Scenario files of the hc08 profile's end-to-end runs (docs/hc08-sim.md "Scenario language").
//
// The HC08 unit (seed 002) has no link to a PC: its only input is the keypad, its outputs are
// the LCD and the four phase lines. So the language says which keys are held when, and what the
// unit must show and do:
//
//   scenario NAME                      title "..."          duration 3 s
//   at T press KEY [xN] [hold T] [bounce]      KEY: set left right plus minus | SA1..SA12 | 0xHH
//   expect at T|end QUANTITY OP V      the unit's state at T (after T's actions)
//   expect end QUANTITY OP V           = expect at end ...
//   expect by T QUANTITY OP V          it holds from T to the end of the run
//   expect between T1 and T2|end QUANTITY OP V         it holds throughout [T1, T2]
//   expect change between T1 and T2|end QUANTITY OP V  its change from T1 to T2 (counts only)
//
// parse() checks the syntax, times, keys, values and that presses do not overlap (the scan
// sees one key at a time), and names file:line on every error; the run (hc08.hpp) gives the
// semantics.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/scenario_text.hpp"

namespace ap::sim::hc08 {

using text::ParseError;

// A key press as the keypad scan sees it (docs/hc08-sim.md "Keys"): the key's code for `hold`
// whole milliseconds from the first scan after T, then 0. With `bounce` the first and the last
// kBounceMs scans of the hold alternate between the code and 0 (seed 002 §4.2.1: bounce "from a
// few to tens of ms", on press and on release).
inline constexpr std::int64_t kDefaultHoldUs = 60'000;
inline constexpr std::uint32_t kBounceMs = 5;
// `xN`: the next press starts this long after the previous one's hold ends (longer than the
// 20 stable scans a release needs before the next press counts, core/hc08/board/keypad.hpp).
inline constexpr std::int64_t kRepeatGapUs = 40'000;

struct Action {
  std::int64_t t_us = 0;
  int line = 0;
  std::string key;            // as written: set, SA1, 0x4E
  std::uint8_t code = 0;      // the scan code the key gives (keypad.hpp key_code)
  std::uint32_t hold_ms = 60;
  bool bounce = false;
};

using text::compare;
using text::Op;
using text::op_text;

// What an expectation reads (docs/hc08-sim.md "Quantities"). The display's: Value (digits 1-4),
// Point (digits after the decimal point), Indicator (X1..X6), Mode (K2 = A, K3 = B), Drive
// (digit 8: 4 or 8), Direction (digit 5: r = +1, l = -1), Error, Adjusted (the last key brought
// the set speed into the motor's range, docs/hc08.md "Menu"). The motor's, from the phase
// lines: Running, Steps (timer-match steps since power-up), Position (half steps, right +),
// Angle (the rotor's angle 0..3595 in tenths), Frequency (Hz of the latest step) and Period
// (its BUSCLK ticks), Dir (of the latest step: +1, -1, 0 before any), Coils (4 bits in
// rotational order), Port (the PTA byte). The keypad's: Presses (debounced presses that
// reached the queue, unused keys included) and Unknown (presses of unused keys).
enum class Quantity : std::uint8_t {
  Value, Point, Indicator, Mode, Drive, Direction, Error, Adjusted,
  Running, Steps, Position, Angle, Frequency, Period, Dir, Coils, Port,
  Presses, Unknown,
};
inline constexpr std::size_t kQuantities = 19;
const char* quantity_name(Quantity q);
// The quantity of a name (quantity_name's inverse); false for an unknown name.
bool quantity_of(const std::string& name, Quantity& q);
// A value as the language writes it (mode A, coils 0011, port 0x18, direction r).
std::string format_value(Quantity q, std::int64_t v);

enum class ExpectKind : std::uint8_t {
  At,          // the value at t_us
  Throughout,  // every value in [t0_us, t_us] (`by T`: [T, end]; `between T1 and T2`)
  Change,      // the value at t_us minus the value at t0_us
};

struct Expectation {
  int line = 0;
  std::string text;            // the line as written, for the report
  ExpectKind kind = ExpectKind::At;
  std::int64_t t0_us = 0;      // Throughout, Change: the window's start
  std::int64_t t_us = 0;       // At: the time; Throughout, Change: the window's end
  Quantity quantity = Quantity::Value;
  Op op = Op::Eq;
  std::int64_t value = 0;
};

struct Scenario {
  std::string file;
  std::string name;
  std::string title;
  std::int64_t duration_us = 0;
  std::vector<Action> actions;            // in time order (xN expanded)
  std::vector<Expectation> expectations;  // in file order
};

Scenario parse(const std::string& text, const std::string& file = "<scenario>");
Scenario parse_file(const std::string& path);

// "10 ms", "0.5 s", "250 us" -> microseconds; false on anything else (negative, finer than 1 us).
bool parse_time(const std::string& number, const std::string& unit, std::int64_t& us);

// The scan code of a key name: set left right plus minus (seed 002 Tab. 4.2), SA1..SA12 (the
// kit's numbering, keypad.hpp), 0xHH (any byte). False for anything else.
bool key_of(const std::string& name, std::uint8_t& code);

}  // namespace ap::sim::hc08
