// The hc08 profile's end-to-end runs over the DDS test bus (docs/hc08-sim.md).
//
//   Board           the firmware core (hc08_board::Board) driven as the MC68HC908LJ12 would
//                   drive it, in virtual time: the keypad scan once per millisecond, the TIM1
//                   match every period_ticks() of BUSCLK while the timer runs, main_loop()
//                   after each; every event recorded (a Row), judged by the SafetyChecker.
//   serve_board()   one Board behind one BoardEndpoint (serve_loop): a plain command advances
//                   the board to its virtual time, environment commands press keys and read
//                   the unit's state. The unit has no PC link, so no bytes travel.
//   run_scenario()  the tester's side: a PcEndpoint stepping virtual time (every 10 ms and at
//                   every action and expectation time), holding the scenario's keys and
//                   judging its expectations; the board on a thread of its own unless joined.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/hc08/board/board.hpp"
#include "pc/dds/bus.hpp"
#include "sim/hc08/safety.hpp"
#include "sim/hc08/scenario.hpp"

namespace ap::sim::hc08 {

// What happened at a row's time: the power-up state, the key line the scan reads changed, a
// debounced key reached the queue (and the main loop ran it), a timer match stepped the motor.
enum class Event : std::uint8_t { Init, Scan, Key, Step };
const char* event_name(Event e);

// The unit after one event (docs/hc08-sim.md "Outputs": one trace.csv row each).
struct Row {
  std::int64_t t = 0;               // units (hc08_safety.hpp) since power-up
  Event event = Event::Init;
  std::uint8_t scan = 0;            // the code the keypad scan reads
  std::uint8_t port = 0;            // PTA
  std::uint8_t coils = 0;           // from PTA3..6
  bool half = false;                // the motor's drive type
  bool running = false;             // the timer runs
  std::int8_t dir = 0;              // of the latest step, from the coils (+1 right)
  std::int64_t period_ticks = 0;    // the latest step's interval (0: no step yet)
  std::int64_t position = 0;        // half steps from the power-up pattern, from the coils
  std::uint64_t steps = 0;
  std::uint32_t presses = 0;
  std::uint32_t unknown = 0;
  std::uint8_t menu = 0;            // hc08_menu::State
  hc08_board::Display display{};
};

// The value of a quantity in a row (docs/hc08-sim.md "Quantities").
std::int64_t value_of(const Row& r, Quantity q);
// The menu state's name (S_DEF, SET_DRIVE, ..., SET_SPEEDx, SET_ANGLEx, seed 002 Tab. 4.3).
const char* menu_name(std::uint8_t state);

// The values a quantity took over [from, to]: the one in force at `from` and every row after.
struct Range {
  std::int64_t min = 0, max = 0;
  std::uint64_t samples = 0;
  std::uint64_t equal = 0;  // samples equal to the value asked about
};

struct BoardOptions {
  std::uint32_t id = 0;
  std::string out_dir;  // trace.csv, waveforms.vcd, plots.svg at shutdown (empty: none)
};

class Board {
 public:
  explicit Board(const BoardOptions& opt);

  // Runs every event at or before t_us: the scans at whole milliseconds, the timer matches,
  // main_loop() after each (at one instant the match first).
  void advance_to(std::int64_t t_us);
  // A key held from now: the scans after now read `code` for hold_ms scans (with bounce, the
  // first and last kBounceMs alternate), then 0. Empty on success, else why it was refused (a
  // key still held: the scan sees one key at a time).
  std::string press(std::uint8_t code, std::uint32_t hold_ms, bool bounce);
  // One environment command (docs/hc08-sim.md "The bus"); returns its text reply.
  std::string env(const std::string& line);
  // Writes the outputs when out_dir is set.
  void finish();

  [[nodiscard]] std::int64_t now() const { return now_; }  // units
  [[nodiscard]] const hc08_board::Board& unit() const { return unit_; }
  [[nodiscard]] const std::vector<Row>& rows() const { return rows_; }
  [[nodiscard]] const SafetyChecker& safety() const { return checker_; }
  [[nodiscard]] std::int64_t quantity(Quantity q) const { return value_of(rows_.back(), q); }
  [[nodiscard]] Range range(Quantity q, std::int64_t from_us, std::int64_t to_us, std::int64_t value) const;

 private:
  void record(Event e);
  std::uint8_t scan_level(std::int64_t scan) const;

  BoardOptions opt_;
  hc08_board::Board unit_{};
  std::int64_t now_ = 0;              // units
  std::int64_t scans_ = 0;            // scans done; scan k runs at k ms
  std::int64_t epoch_ = 0;            // the timer's last start or match
  std::uint8_t scan_ = 0;             // the level the last scan read
  // The key being held: scans [key_first_, key_first_ + key_hold_) read it.
  std::int64_t key_first_ = 0;
  std::uint32_t key_hold_ = 0;
  std::uint8_t key_code_ = 0;
  bool key_bounce_ = false;
  std::int64_t last_step_ = 0;        // units; the latest step, or the motion's start
  std::int64_t position_ = 0;
  std::int8_t dir_ = 0;
  std::int64_t period_ = 0;
  std::uint64_t steps_ = 0;
  std::uint32_t presses_ = 0;
  SafetyChecker checker_;
  std::vector<Row> rows_;
};

// The board side until a shutdown command, `idle_timeout` without a command, or *stop.
// Returns 0 on an orderly shutdown.
int serve_board(const dds::ParticipantPtr& participant, const BoardOptions& opt, std::chrono::milliseconds idle_timeout,
                const std::atomic<bool>* stop = nullptr);

struct RunOptions {
  std::string out_root = "out/sim/hc08";  // outputs under out_root/NAME/ (empty: none)
  std::int64_t step_us = 10'000;          // lockstep period
  std::optional<std::uint32_t> domain;    // default: claim a free one (DomainLease)
  bool join = false;                      // the board runs elsewhere (axisproof sim board --profile hc08)
  std::ostream* log = nullptr;
};

struct RunResult {
  bool pass = false;
  std::vector<std::string> failures;  // expectations, safety properties, refused keys, the link
  std::vector<std::string> passed;    // expectations met
  std::int64_t vtime_us = 0;
  double wall_s = 0.0;
  std::uint64_t bus_round_trips = 0;
  std::uint64_t events = 0;           // checked by the board's safety checker
  std::uint64_t steps = 0;
  std::uint64_t presses = 0;
  std::uint64_t dropped = 0;          // keys the unit's queue dropped
  std::uint32_t domain = 0;
  std::string out_dir;
};

// Runs one scenario; throws ap::dds::Error / std::runtime_error on a bus failure.
RunResult run_scenario(const Scenario& s, const RunOptions& opt);

// The verdict as text (also out_dir/report.txt).
std::string format_report(const Scenario& s, const RunResult& r);

// The outputs of a board's rows (docs/hc08-sim.md "Outputs").
void write_trace_csv(const std::vector<Row>& rows, const std::string& path);
void write_vcd(const std::vector<Row>& rows, const std::string& path);
void write_svg(const std::vector<Row>& rows, const std::string& title, const std::string& path);
// A row's time in ns (the VCD's timescale), to the nearest ns.
constexpr std::uint64_t ns_of(std::int64_t units) {
  return static_cast<std::uint64_t>((units * 1000 + kUnitsPerUs / 2) / kUnitsPerUs);
}

}  // namespace ap::sim::hc08
