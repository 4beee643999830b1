// Scenario files for the simulated PC (docs/sim.md; format in docs/scenarios.md).
//
// A scenario is a header (name, duration, boards, timing, board setup, link faults), timed user
// actions ("at 1.5 s goto x 20 mm") and expectations ("expect at 6 s x.pos == 20 mm tol 5 um").
// parse() checks syntax, units, axes, board indices and that each expectation's value has the
// dimension of its subject; the simulated PC gives the semantics. All quantities are stored in
// canonical units: um, um/s, um/s2, us, mV, mA, mdegC, mdeg, % (percent) or plain numbers.
// to_text() prints the canonical form; parse(to_text(s)) == s.
//
// The language is read on the shared kit (sim/scenario_text.hpp): its words, strings and
// comments, its comparisons (Op) and its errors (ParseError, naming file:line) are the kit's.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sim/scenario_text.hpp"

namespace ap::sim::xy::scenario {

using text::Op;
using text::ParseError;

enum class Dim : std::uint8_t { none, length, speed, accel, time, voltage, current, temperature, angle, ratio };

struct Quantity {
  double value = 0.0;   // in the canonical unit of dim
  Dim dim = Dim::none;
  friend bool operator==(const Quantity&, const Quantity&) = default;
};

// A word (enum-like: "reached", "+", "on", "fast", ...) or a quantity.
using Value = std::variant<std::string, Quantity>;

struct Target {
  bool all = true;            // every board (the default)
  std::uint32_t board = 0;    // when !all: "@N"
  friend bool operator==(const Target&, const Target&) = default;
};

enum class Verb : std::uint8_t {
  jog,            // jog AXIS +|- [fast|slow]        manual move, held until stop
  stop,           // stop AXIS
  go_to,          // goto AXIS LENGTH [fast|slow]    absolute move (fast: goto, slow: goto_slow)
  move,           // move AXIS +-LENGTH [fast|slow]  relative move (move / move_slow)
  home,           // home AXIS
  set_speed,      // set speed fast|slow SPEED
  set_accel,      // set accel ACCEL
  save,           // save                            store the parameters in FRAM
  reboot,         // reboot                          power-cycle the board (FRAM kept)
  subscribe,      // subscribe NAME
  unsubscribe,    // unsubscribe NAME
  charger,        // charger plug|unplug
  usb,            // usb plug|unplug
  battery,        // battery VOLTAGE
  temperature,    // temperature TEMP
  rotate,         // rotate ANGLE                    IMU rotation of the platform
  ble,            // ble shutdown|standby|connected|session  (Tab. 7-2)
  tmc,            // tmc AXIS FIELD NUMBER           register field write (e.g. IRUN 12)
  link_cut,       // link cut [DURATION]             no frames either way (for DURATION or until restore)
  link_restore,   // link restore
  peripherals,    // peripherals on|off
  endstop,        // endstop AXIS min|max on|off     force a Hall sensor
  button,         // button press|hold
  raw,            // raw "TEXT"                      send this command frame verbatim
  gcode,          // gcode "FILE" [thesis|tolerant]  run a G-code program as path frames (docs/cnc.md)
};

struct Action {
  std::int64_t t_us = 0;
  Target target;
  Verb verb = Verb::stop;
  char axis = 0;                   // 'x' / 'y' for axis verbs, else 0
  std::string word;                // +/-, fast/slow, on/off, NAME, FIELD, raw text, ...
  std::string word2;               // second word (jog speed level, endstop on/off)
  std::optional<Quantity> amount;  // LENGTH, SPEED, ACCEL, VOLTAGE, DURATION, NUMBER, ...
  int line = 0;
  friend bool operator==(const Action&, const Action&) = default;
};

enum class When : std::uint8_t { at, always, between, by, end };

struct Expectation {
  When when = When::at;
  std::int64_t t_us = 0;    // at / by / between: from
  std::int64_t t2_us = 0;   // between: to
  Target target;
  std::string subject;      // e.g. "x.pos", "board.state", "tmc.x.IRUN", "sub.battery", "gaps"
  Op op = Op::Eq;
  Value value;
  std::optional<Quantity> tol;
  int line = 0;
  friend bool operator==(const Expectation&, const Expectation&) = default;
};

enum class FaultKind : std::uint8_t { drop, duplicate, reorder, corrupt, delay };
enum class Direction : std::uint8_t { both, to_board, to_pc };

struct Fault {
  FaultKind kind = FaultKind::drop;
  Quantity amount;             // rate in % (drop, duplicate, reorder, corrupt) or time (delay)
  std::optional<Quantity> jitter;   // delay only
  Direction dir = Direction::both;
  std::int64_t from_us = 0;
  std::optional<std::int64_t> to_us;   // default: end of run
  int line = 0;
  friend bool operator==(const Fault&, const Fault&) = default;
};

struct Setup {                 // "board KEY ..." lines: the board's state before the run
  std::string key;             // battery, charger, usb, ble, temperature, pos, endstop, param, fram
  char axis = 0;
  std::string word;            // e.g. plugged, session, min, lead, accel
  std::optional<Quantity> amount;
  int line = 0;
  friend bool operator==(const Setup&, const Setup&) = default;
};

enum class Timing : std::uint8_t { lockstep, realtime };

struct Scenario {
  std::string name;
  std::string title;
  std::uint32_t boards = 1;
  std::int64_t duration_us = 0;
  std::int64_t period_us = 100'000;   // PC command period (thesis: 100 ms)
  Timing timing = Timing::lockstep;
  std::uint64_t seed = 1;
  std::uint16_t first_seq = 0;        // the PC's first command seq (docs/protocol.md "Delivery")
  std::uint32_t baud = 115'200;
  std::vector<Setup> setup;
  std::vector<Fault> faults;
  std::vector<Action> actions;          // in time order
  std::vector<Expectation> expectations;
  friend bool operator==(const Scenario&, const Scenario&) = default;
};

// Evaluates one expectation's comparison against an observed value (the simulated PC decides
// when). Quantities: == is |a - v| <= tol, != is |a - v| > tol, < / <= / > / >= are widened by
// tol (a < v + tol, a <= v + tol, a > v - tol, a >= v - tol); tol defaults to 0. Words compare
// with == and != only. Throws std::invalid_argument on a word/quantity or dimension mismatch.
bool holds(const Expectation& e, const Value& actual);

Scenario parse(std::string_view text, const std::string& file = "<scenario>");
Scenario parse_file(const std::string& path);
std::string to_text(const Scenario& s);

// Canonical unit name of a dimension ("um", "um/s", ...; "" for none).
std::string_view unit_name(Dim d);
// The dimension a subject's value must have (Dim::none for words and counts); nullopt if the
// subject is unknown.
std::optional<Dim> subject_dim(std::string_view subject);
std::string_view to_string(Verb v);

}  // namespace ap::sim::xy::scenario
