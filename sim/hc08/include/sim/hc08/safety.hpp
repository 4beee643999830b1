// The hc08 run's safety properties (docs/hc08-sim.md "Safety checks"), judged on every event of
// every run from what the unit put on its four phase lines and when. A violation fails the run.
// The checker knows the motor only from the documents, not from the core: the half-step table
// of docs/hc08.md "Excitation" gives each coil pattern its rotational position, and the step
// times give the step frequency.
//
//   maxfreq   no step comes sooner than the motor's maximum operating frequency allows: 800 Hz
//             in full step, 1700 Hz in half step [T Tab. 3.1].
//   start     the first step of a motion comes at or below the start frequency (280 / 560 Hz,
//             the catalogue's maximum start frequencies [T Tab. 3.1], docs/hc08.md "Ramp").
//   ramp      above the start frequency the period changes by at most accelStep = 64 BUSCLK
//             ticks from one step to the next [T §5.3.2; 64 is docs/hc08.md's D], the period
//             counted as at most the start frequency's.
//   reverse   the direction of rotation changes only where the step before or the step after
//             the change is at or below the start frequency (docs/hc08.md "Ramp").
//   stop      a motion stops only after a step at or below the start frequency.
//   coils     every pattern on the coils is a rest position of the half-step table and never
//             two opposite coils; a step moves it one half step (half step) or two (full step);
//             between steps it changes only at rest, by a drive change half a step forward
//             (docs/hc08.md "Excitation").
//
// "At or below the start frequency" is a period of at least the start frequency's period as the
// timer makes it, rounded to the nearest BUSCLK tick: 8 777 ticks for 280 Hz, 4 389 for 560 Hz.
// Time is counted in units of 1/1 536 000 000 s, which divide both 1 us (1 536) and one BUSCLK
// tick (625), so every period is exact.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ap::sim::hc08 {

inline constexpr std::int64_t kUnitsPerSecond = 1'536'000'000;
inline constexpr std::int64_t kUnitsPerUs = 1'536;
inline constexpr std::int64_t kUnitsPerMs = 1'536'000;
inline constexpr std::int64_t kBusHz = 2'457'600;  // BUSCLK [T §4.5]
inline constexpr std::int64_t kUnitsPerTick = kUnitsPerSecond / kBusHz;  // 625
static_assert(kUnitsPerTick * kBusHz == kUnitsPerSecond);
static_assert(kUnitsPerUs * 1'000'000 == kUnitsPerSecond);

inline constexpr std::int64_t kStartHzFull = 280, kStartHzHalf = 560;   // [T Tab. 3.1]
inline constexpr std::int64_t kMaxHzFull = 800, kMaxHzHalf = 1700;      // [T Tab. 3.1]
inline constexpr std::int64_t kAccelTicks = 64;                        // accelStep [D]
// The start frequency's period in BUSCLK ticks, to the nearest tick.
constexpr std::int64_t start_period_ticks(bool half) {
  const std::int64_t hz = half ? kStartHzHalf : kStartHzFull;
  return (kBusHz + hz / 2) / hz;
}
static_assert(start_period_ticks(false) == 8777 && start_period_ticks(true) == 4389);

// The rotational position 0..7 (in half steps) of a coil pattern, from the half-step table
// 0001 0011 0010 0110 0100 1100 1000 1001 (docs/hc08.md); nothing for any other pattern.
std::optional<int> half_position(std::uint8_t coils);
// How far the rotor moves from pattern `from` to pattern `to`, in half steps -3..4 (forward +);
// 0 when either is no rest position.
int half_steps(std::uint8_t from, std::uint8_t to);
// The coil pattern (bit k = the coil at rotational position k) of a PTA byte with the default
// phase order: phase 1..4 on PTA3..PTA6 at positions 0..3 (docs/hc08.md "Excitation").
constexpr std::uint8_t coils_of_port(std::uint8_t port) { return static_cast<std::uint8_t>((port >> 3) & 0x0FU); }

// What the checker sees after each event of the run.
struct Sample {
  std::int64_t t = 0;        // units since power-up
  bool step = false;         // the event was a timer match
  std::uint8_t coils = 0;    // after the event
  bool half = false;         // the drive type in force (half step)
  bool running = false;      // the timer runs after the event
};

class SafetyChecker {
 public:
  // Feed every event in time order; the first sample is the power-up state.
  void check(const Sample& s);
  [[nodiscard]] const std::vector<std::string>& violations() const { return violations_; }
  [[nodiscard]] std::uint64_t events() const { return events_; }
  [[nodiscard]] std::uint64_t steps() const { return steps_; }

 private:
  void fail(std::int64_t t, const std::string& what);

  bool started_ = false;         // the power-up sample was seen
  std::uint8_t coils_ = 0;
  bool running_ = false;
  std::int64_t motion_start_ = 0;
  std::int64_t last_step_ = 0;   // of this motion
  std::int64_t interval_ = 0;    // the latest step's interval in units (0: no step in this motion)
  int dir_ = 0;                  // the latest step's direction in this motion (0: none)
  std::uint64_t events_ = 0, steps_ = 0;
  std::vector<std::string> violations_;
};

}  // namespace ap::sim::hc08
