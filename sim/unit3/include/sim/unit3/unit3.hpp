// The unit3 profile's end-to-end runs over the DDS test bus (docs/unit3-sim.md).
//
//   Board           the firmware core (unit3_board::Unit) and its EEPROM image, driven as the
//                   ATmega2560 would be: one tick() per 1 ms, the UART bytes at 19200 8N1 both
//                   ways, the joystick, endstops and buttons; every tick sampled, traced and
//                   judged by the SafetyChecker.
//   serve_board()   one Board behind one BoardEndpoint: answers every bus command with one echo
//                   (lockstep, docs/dds.md). The unit's bytes travel unchanged; the bus's
//                   telemetry of the echo is left default.
//   run_scenario()  the PC side: a PcEndpoint stepping virtual time every 10 ms (and at every
//                   action and expectation time), writing the scenario's bytes, sending its
//                   environment commands, reading the unit's replies and judging the
//                   expectations; the boards on a thread of their own unless joined.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/unit3/board/unit.hpp"
#include "pc/dds/bus.hpp"
#include "sim/serve_loop.hpp"
#include "sim/unit3/safety.hpp"
#include "sim/unit3/scenario.hpp"

namespace ap::sim::unit3 {


// The UART at 19200 8N1 [T §2.1]: 10 bit times per byte, 1920 bytes/s. Line time is counted in
// 1/12 us (12 MHz divides both 1 us and one bit time, 625 units), so byte k of a burst ends
// exactly at k * 6250 units (520.83 us) with no rounding drift.
inline constexpr std::int64_t kLineUnitsPerUs = 12;
inline constexpr std::int64_t kByteUnits = 6250;

struct BoardOptions {
  std::uint32_t id = 0;
  Eeprom eeprom = Eeprom::Default;
  std::string out_dir;  // trace.csv, waveforms.vcd, plots.svg at shutdown (empty: none)
};

class Board {
 public:
  explicit Board(const BoardOptions& opt);

  // Runs 1 ms ticks up to `t_us` (whole ticks only: the tick ending at t_us included).
  void advance_to(std::int64_t t_us);
  // Bytes the PC wrote at `t_us` (not before now): they arrive one per 520.83 us after the
  // line's earlier bytes.
  void rx(const std::vector<std::uint8_t>& bytes, std::int64_t t_us);
  // Bytes the unit's UART has finished sending by now (at most `max`).
  std::vector<std::uint8_t> take_tx(std::size_t max);
  // One environment command (docs/unit3-sim.md "The bus"); returns its text reply.
  std::string env(const std::string& line);
  // Writes the outputs when out_dir is set.
  void finish();

  [[nodiscard]] std::int64_t now_us() const { return static_cast<std::int64_t>(t_ms_) * 1000; }
  [[nodiscard]] const unit3_board::Unit& unit() const { return *unit_; }
  [[nodiscard]] const std::vector<TickSample>& samples() const { return samples_; }
  [[nodiscard]] const SafetyChecker& safety() const { return checker_; }
  [[nodiscard]] std::uint64_t pulses(std::size_t a) const { return pulses_[a < kAxes ? a : 0]; }

 private:
  void tick();
  std::string state_of(std::size_t a) const;

  BoardOptions opt_;
  std::array<std::uint8_t, unit3_settings::kImageSize> eeprom_{};
  std::optional<unit3_board::Unit> unit_;
  unit3_board::Inputs in_{};
  // The six endstop pins as the port reads them: high = open (the pull-ups), a closed switch
  // pulls its pin low; each tick reads them into in_.endstops (unit3_board::endstops_from_pins).
  std::uint8_t endstop_pins_ = unit3_board::kEndstopPins;
  std::uint64_t t_ms_ = 0;
  std::deque<std::pair<std::int64_t, std::uint8_t>> rx_line_;  // (arrival in line units, byte)
  std::int64_t rx_free_ = 0;                                   // the line's next free time
  std::int64_t tx_free_ = 0;
  std::deque<std::pair<std::int64_t, std::uint8_t>> tx_line_;  // (end on the line, byte), not yet echoed
  std::array<std::uint64_t, kAxes> pulses_{};
  std::uint32_t power_cycles_ = 0;
  std::uint32_t tx_dropped_ = 0;  // of earlier power-ups
  SafetyChecker checker_;
  std::vector<TickSample> samples_;
};

// The board side until a shutdown command, `idle_timeout` without a command, or *stop.
// Returns 0 on an orderly shutdown.
int serve_board(const dds::ParticipantPtr& participant, const BoardOptions& opt, std::chrono::milliseconds idle_timeout,
                const std::atomic<bool>* stop = nullptr);

struct RunOptions {
  std::string out_root = "out/sim/unit3";  // outputs under out_root/NAME/ (empty: none)
  std::int64_t step_us = 10'000;           // lockstep period
  std::optional<std::uint32_t> domain;     // default: claim a free one (DomainLease)
  bool join = false;                       // the board runs elsewhere (axisproof sim board --profile unit3)
  std::ostream* log = nullptr;
};

struct Reply {
  std::int64_t t_us = 0;  // the echo that brought its `;`
  std::string bytes;
};

struct RunResult {
  bool pass = false;
  std::vector<std::string> failures;    // expectations, safety properties, link problems
  std::vector<std::string> passed;      // expectations met
  std::vector<Reply> replies;           // every line the PC received, in order
  std::int64_t vtime_us = 0;
  double wall_s = 0.0;
  std::uint64_t bus_round_trips = 0;
  std::uint64_t ticks = 0;              // the board's safety checker
  std::array<std::uint64_t, kAxes> pulses{};
  std::uint32_t domain = 0;
  std::string out_dir;
};

// Runs one scenario; throws ap::dds::Error / std::runtime_error on a bus failure.
RunResult run_scenario(const Scenario& s, const RunOptions& opt);

// The verdict as text (also out_dir/report.txt).
std::string format_report(const Scenario& s, const RunResult& r);

// The outputs of a board's samples (docs/unit3-sim.md "Outputs").
void write_trace_csv(const std::vector<TickSample>& samples, const std::string& path);
void write_vcd(const std::vector<TickSample>& samples, const std::string& path);
void write_svg(const std::vector<TickSample>& samples, const std::string& title, const std::string& path);

}  // namespace ap::sim::unit3
