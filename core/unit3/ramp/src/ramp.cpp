// The ramp table is constexpr (ramp.hpp) so the firmware, the tests and the proofs read one
// definition; the timer's advance is here.
#include "core/unit3/ramp/ramp.hpp"

namespace ap::unit3_ramp {

// The table's ends, as docs/unit3.md states them: 25 Hz = TOP 9999, 800 Hz = TOP 312.
static_assert(kTable.top[0] == 9999);
static_assert(kTable.top[kEntries - 1] == 312);

std::uint32_t Timer::advance(std::uint32_t clocks, std::uint32_t& first_at) {
  std::uint32_t matches = 0;
  std::uint32_t done = 0;
  first_at = 0;
  while (done < clocks) {
    // Clocks until TCNT equals TOP and the next clock clears it; past TOP it wraps first.
    const std::uint32_t to_match = count_ <= top_ ? (top_ - count_) + 1U : (65536U - count_) + top_ + 1U;
    if (clocks - done < to_match) {
      count_ = static_cast<std::uint16_t>(count_ + (clocks - done));
      break;
    }
    done += to_match;
    count_ = 0;
    if (matches++ == 0) first_at = done;
  }
  return matches;
}

}  // namespace ap::unit3_ramp
