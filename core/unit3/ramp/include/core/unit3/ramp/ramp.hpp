#pragma once
// The unit's step timing (seed 001 §3.2, §3.5; docs/unit3.md "Ramp and step timer"): one
// 16-bit timer per axis in CTC mode whose TOP (OCRnA) comes from a 32-entry ramp table, and
// the rule that moves an axis through the table one entry per ramp interval.
// The thesis gives the table only as a graph (Obr. 17) and two sentences on it
// (../shared/seeds/001_*.txt:1061-1067): at low speeds the motors "accelerate much more slowly
// than at higher speeds" (so the stick can position precisely), and they "accelerate
// linearly". Read together [D, docs/unit3.md "Ramp and step timer"]: the frequency step from
// one entry to the next grows by the same kStepGrowthHz at every entry (no jump in the
// acceleration), from kFirstStepHz between entries 0 and 1 to four times that between 30 and
// 31; the ends stay 25 Hz and 800 Hz. The index moves by at most one entry per kRampMs.
// Integer-only; the ranges below are what the tests and proofs speak about.
#include <array>
#include <cstdint>

namespace ap::unit3_ramp {

inline constexpr std::uint32_t kCpuHz = 16'000'000;               // crystal [T §1]
inline constexpr std::uint32_t kPrescaler = 64;                    // [D]
inline constexpr std::uint32_t kTimerHz = kCpuHz / kPrescaler;     // 250 kHz, 4 us per clock
inline constexpr std::uint8_t kEntries = 32;                       // indices 0..31 [T §3.5]
inline constexpr std::uint32_t kStartHz = 25;                      // entry 0 [D]
inline constexpr std::uint32_t kFirstStepHz = 10;                  // entry 1 - entry 0 [D]
inline constexpr std::uint32_t kStepGrowthHz = 1;                  // each step 1 Hz above the last [D]
inline constexpr std::uint32_t kRampMs = 10;                       // one entry per interval [D]
inline constexpr std::uint32_t kTickMs = 1;                        // the main loop's period [D]
inline constexpr std::uint32_t kTickClocks = kTimerHz / 1000 * kTickMs;     // 250
inline constexpr std::uint32_t kIntervalClocks = kTickClocks * kRampMs / kTickMs;  // 2500

// The frequency entry i stands for, and the TOP that makes it: f = kTimerHz / (TOP + 1), TOP
// rounded to the nearest clock. The steps 10, 11, ..., 40 Hz sum to f(i) = 25 + 10 i + i (i - 1) / 2:
// 25, 35, 46, ... 760, 800 Hz (i (i - 1) is even, so the division is exact; i * i >= i, no wrap).
constexpr std::uint32_t entry_hz(std::uint8_t i) {
  return kStartHz + kFirstStepHz * i + kStepGrowthHz * ((std::uint32_t{i} * i - i) / 2U);
}
static_assert(entry_hz(kEntries - 1) == 800);  // the documented top speed
constexpr std::uint16_t top_for(std::uint32_t hz) {
  return static_cast<std::uint16_t>((kTimerHz + hz / 2) / hz - 1);
}

struct Table {
  std::array<std::uint16_t, kEntries> top{};    // OCRnA per entry, falling with the index
  std::array<std::uint32_t, kEntries> stop{};   // see below
};

// stop[i]: the most pulses an axis can send while it runs one ramp interval at each entry
// i, i-1, ..., 1 (ceil(kIntervalClocks / (TOP + 1)) per interval). A move whose remaining
// pulses exceed stop[n] can run its next interval at entry n and still reach entry 0 before
// its last pulse (next_entry()).
constexpr Table make_table() {
  Table t{};
  std::uint32_t sum = 0;
  for (std::uint8_t i = 0; i < kEntries; ++i) {
    t.top[i] = top_for(entry_hz(i));
    const std::uint32_t period = t.top[i] + 1U;
    if (i > 0) sum += (kIntervalClocks + period - 1) / period;
    t.stop[i] = sum;
  }
  return t;
}
inline constexpr Table kTable = make_table();

// At most one pulse per main-loop tick, so a tick reports its pulse with one clock offset.
static_assert(kTable.top[kEntries - 1] + 1U > kTickClocks);

// What an axis does in its next ramp interval.
struct Next {
  bool stop = false;       // leave the table: the axis is at entry 0 and stopping was asked
  std::uint8_t entry = 0;  // the entry of the next interval
  friend constexpr bool operator==(const Next&, const Next&) = default;
};

// The ramp rule, applied at every interval boundary. `entry` the current entry; `target` the
// entry asked for (the stick's index, or the top of the table for a PC move); `stop` when the
// axis is asked to stop (the stick in the dead band or reversed); `remaining` the pulses a PC
// move still has to send (kNoEnd for the joystick). The entry moves by at most one; a PC move
// goes no higher than lets it reach entry 0 before its last pulse, so every move ends at the
// start speed (docs/unit3.md: the ramp-down the thesis does not describe).
inline constexpr std::uint64_t kNoEnd = ~std::uint64_t{0};
constexpr Next next_entry(std::uint8_t entry, std::uint8_t target, bool stop, std::uint64_t remaining) {
  if (entry >= kEntries) entry = kEntries - 1;
  if (target >= kEntries) target = kEntries - 1;
  if (stop) return entry == 0 ? Next{true, 0} : Next{false, static_cast<std::uint8_t>(entry - 1)};
  std::uint8_t n = target > entry ? static_cast<std::uint8_t>(entry + 1)
                   : target < entry ? static_cast<std::uint8_t>(entry - 1)
                                    : entry;
  const std::uint8_t floor = entry > 0 ? static_cast<std::uint8_t>(entry - 1) : 0;
  while (n > floor && kTable.stop[n] >= remaining) --n;
  return {false, n};
}

// One axis's 16-bit timer in CTC mode: TCNT counts timer clocks up to TOP; the clock after it
// equals TOP clears it and the compare interrupt sends one STEP pulse (seed 001 §3.2).
class Timer {
 public:
  // Restart from TCNT = 0 at the given TOP (an axis starting from rest).
  void start(std::uint16_t top) {
    count_ = 0;
    top_ = top;
  }
  // A new TOP while running. Were TCNT already past it, the compare would not come until
  // TCNT wrapped through 65536 (262 ms at 250 kHz): the firmware then sets TCNT to the new
  // TOP, so the pulse that is already due comes on the next clock.
  void set_top(std::uint16_t top) {
    top_ = top;
    if (count_ > top_) count_ = top_;
  }
  // Runs `clocks` timer clocks. Returns how many compare matches they held; `first_at` gets
  // the clock (1-based within these clocks) of the first one.
  std::uint32_t advance(std::uint32_t clocks, std::uint32_t& first_at);
  std::uint16_t count() const { return count_; }
  std::uint16_t top() const { return top_; }

 private:
  std::uint16_t count_ = 0;
  std::uint16_t top_ = kTable.top[0];
};

}  // namespace ap::unit3_ramp
