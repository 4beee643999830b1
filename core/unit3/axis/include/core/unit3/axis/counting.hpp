#pragma once
// The unit's step counting (seed 001 §3.3-3.4, docs/unit3.md "Counting"): a 64-bit counter per
// axis in 1/32-step counts, the DRV8825 step modes, the thread pitches and the position in µm.
// Integer-only; every range below is what the proofs and tests speak about.
#include <array>
#include <cstdint>

namespace ap::unit3_axis {

// A step mode d = 0..5 is a step of 1/2^d; each STEP pulse moves the counter by 32 >> d [T].
inline constexpr std::uint8_t kModes = 6;
inline constexpr std::uint32_t kCountsPerFullStep = 32;          // [T]
inline constexpr std::uint32_t kStepsPerRev = 200;               // 1.8° motors [T]
inline constexpr std::uint32_t kCountsPerRev = kStepsPerRev * kCountsPerFullStep;  // 6400 [T eq. 5]

// DRV8825 MODE2..0 pin levels for each mode: the mode digit's binary value [T Tab. 7].
struct ModePins {
  bool m2, m1, m0;
  friend constexpr bool operator==(const ModePins&, const ModePins&) = default;
};
inline constexpr std::array<ModePins, kModes> kModePins = {{
    {false, false, false}, {false, false, true}, {false, true, false},
    {false, true, true},   {true, false, false}, {true, false, true},
}};
constexpr std::uint32_t counts_per_pulse(std::uint8_t mode) { return kCountsPerFullStep >> mode; }

// Thread pitch per index, µm per revolution. The thesis gives two pitches, M2 = 0.4 mm and
// M6 = 1 mm (001_*.txt:1037-1039), and two places, index 0 = M2 and index 6 = M10
// (001_*.txt:1326-1328). The rest is [D]: the sizes M3, M4, M5 and M8 between them (so M6 sits at
// index 4) and the ISO coarse pitches of M3, M4, M5, M8 and M10. Each entry says which of its
// two halves the thesis states.
inline constexpr std::uint8_t kThreads = 7;
struct Thread {
  const char* name;
  std::uint32_t pitch_um;
  bool pitch_from_thesis;  // the pitch is the thesis's
  bool index_from_thesis;  // the thesis puts this thread at this index
};
inline constexpr std::array<Thread, kThreads> kThreadTable = {{
    {"M2", 400, true, true}, {"M3", 500, false, false}, {"M4", 700, false, false}, {"M5", 800, false, false},
    {"M6", 1000, true, false}, {"M8", 1250, false, false}, {"M10", 1500, false, true},
}};

// The counter's range: what the unit reports (18 digits, docs/unit3.md "The wire"). A move
// that would leave it is refused; 10^18 + 10^15 < 2^63, so counter ± count never wraps.
inline constexpr std::int64_t kMaxCounter = 999'999'999'999'999'999LL;
inline constexpr std::uint64_t kMaxMoveCount = 999'999'999'999'999ULL;  // the wire's 15 digits

enum class Error : std::uint8_t {
  None = 0,
  BadMode,        // mode digit > 5
  NotMultiple,    // the count is not a whole number of pulses in this mode [D]
  TooFar,         // count > 15 digits
  CounterRange,   // the move would take the counter past ±(10^18 - 1)
};

struct Plan {
  Error error = Error::None;
  std::uint64_t pulses = 0;  // STEP pulses to send
  std::int64_t target = 0;   // the counter after them
};

// A relative move of `count` counts in direction dir (+1 or -1) from `counter` in step mode
// `mode`. Refused (error set, nothing else meaningful) when it cannot be made exactly.
constexpr Plan plan_move(std::int64_t counter, std::int8_t dir, std::uint64_t count, std::uint8_t mode) {
  if (mode >= kModes) return {Error::BadMode, 0, counter};
  if (count > kMaxMoveCount) return {Error::TooFar, 0, counter};
  const std::uint32_t per = counts_per_pulse(mode);
  if (count % per != 0) return {Error::NotMultiple, 0, counter};
  const auto delta = static_cast<std::int64_t>(count);  // < 2^50
  const std::int64_t target = dir < 0 ? counter - delta : counter + delta;
  if (target > kMaxCounter || target < -kMaxCounter) return {Error::CounterRange, 0, counter};
  return {Error::None, count / per, target};
}

// Position of a counter in µm (eq. 5: count / 6400 * pitch), rounded to the nearest µm, half
// away from zero. Split so that no product exceeds 2^63: |count / 6400| <= 1.6e14. A thread
// index past the table (the settings never hold one) reads as M2, never past the table.
constexpr std::int64_t position_um(std::int64_t counter, std::uint8_t thread) {
  const std::int64_t pitch = kThreadTable[thread < kThreads ? thread : 0].pitch_um;
  const std::int64_t revs = counter / static_cast<std::int64_t>(kCountsPerRev);
  const std::int64_t rest = counter % static_cast<std::int64_t>(kCountsPerRev);  // same sign as counter
  const std::int64_t num = rest * pitch;                                       // |num| < 6400 * 1500
  const std::int64_t half = static_cast<std::int64_t>(kCountsPerRev) / 2;
  const std::int64_t frac = (num >= 0 ? num + half : num - half) / static_cast<std::int64_t>(kCountsPerRev);
  return revs * pitch + frac;
}

}  // namespace ap::unit3_axis
