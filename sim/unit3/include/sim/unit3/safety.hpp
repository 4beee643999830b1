// The unit3 run's safety properties (docs/unit3-sim.md "Safety checks"), judged on every tick
// of every run from what the unit put on its pins and its axis state. A violation fails the run.
//
//   reverse   the DIR pin of an axis changes only from ramp entry 0: while it runs, only when
//             it ran at entry 0 in the tick before; from rest, only when its last stop was
//             from entry 0 (a ramp to entry 0, or a PC move's end at the entry-0 period) or
//             by an endstop (the thesis's interrupt stop, seed 001 §3.9). Decelerate before
//             reverse: the thesis's motors "accelerate and brake smoothly" [T §3.5].
//   ramp      a start is at entry 0 and the entry then moves by at most one per ramp interval
//             (10 ms), the linear acceleration of [T §3.5] as core/unit3/ramp fixes it.
//   stop      a PC move's last pulse comes one entry-0 period (10000 timer clocks, 40 ms)
//             after the pulse before it (or its start): the move ends at the start speed
//             (the ramp-down of core/unit3/board). Measured on the STEP pin, not the state.
//   endstop   no STEP pulse towards a closed endstop.
//   gap       a running axis pulses at least once per entry-0 period: no gap between two
//             pulses (or a start and its first pulse) exceeds 10000 timer clocks (40 ms).
//
// Time: tick t (1-based, the unit's t-th 1 ms main-loop pass) covers timer clocks
// ((t-1)*250, t*250]; a pulse at `pulse_at` (1..250) is at clock (t-1)*250 + pulse_at.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/unit3/board/unit.hpp"

namespace ap::sim::unit3 {

inline constexpr std::size_t kAxes = unit3_board::kAxes;
inline constexpr std::int64_t kTickClocks = unit3_ramp::kTickClocks;                     // 250
inline constexpr std::int64_t kSlowestPeriod = unit3_ramp::kTable.top[0] + 1;            // 10000
inline constexpr std::int64_t kRampTicks = unit3_ramp::kRampMs / unit3_ramp::kTickMs;    // 10

struct AxisSample {
  unit3_board::Source source = unit3_board::Source::Idle;
  std::uint8_t entry = 0;
  std::int8_t dir = 1;
  std::uint8_t mode = 0;  // the MODE2..0 pins as a number (the step mode digit, seed 001 Tab. 7)
  std::int64_t counter = 0;
  std::uint64_t remaining = 0;
  std::uint8_t pulses = 0;
  std::uint16_t pulse_at = 0;
  bool running = false;
};

struct TickSample {
  std::uint64_t t_ms = 0;          // the tick's end, ms since the run began
  std::uint8_t endstops = 0;       // the inputs of this tick (unit3_board::endstop_bit)
  std::array<AxisSample, kAxes> axis{};
};

// The sample of one tick of a unit, read after its tick().
TickSample sample_of(const unit3_board::Unit& u, std::uint64_t t_ms, std::uint8_t endstops);

class SafetyChecker {
 public:
  // Feed every tick in order (t_ms increasing by 1, except across a power cycle).
  void check(const TickSample& s);
  // The unit lost power: the motors stop with it; the checks start again from rest.
  void power_cycle();
  [[nodiscard]] const std::vector<std::string>& violations() const { return violations_; }
  [[nodiscard]] std::uint64_t ticks() const { return ticks_; }

 private:
  struct Track {
    bool running = false;      // in the previous tick
    std::int8_t dir = 1;       // DIR pin in the previous tick
    std::uint8_t entry = 0;    // entry in the previous tick
    unit3_board::Source source = unit3_board::Source::Idle;
    bool stopped = false;      // has stopped at least once since power-up
    bool stop_ok = true;       // that stop was from entry 0 or by an endstop
    std::int8_t stop_dir = 1;
    std::uint8_t stop_entry = 0;
    std::uint64_t last_change = 0;  // tick of the last entry change (or of the start)
    std::int64_t last_clock = 0;    // clock of the last pulse (or of the start)
  };
  void fail(const TickSample& s, std::size_t a, const std::string& what);

  std::array<Track, kAxes> track_{};
  std::vector<std::string> violations_;
  std::uint64_t ticks_ = 0;
};

}  // namespace ap::sim::unit3
