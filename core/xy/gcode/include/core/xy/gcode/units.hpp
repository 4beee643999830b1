// Unit conversion of parsed values (1e-4 of mm or inch) to micrometres and um/s
// (docs/gcode.md §Units). Integer only; every result is rounded half away from zero.
#pragma once

#include <cstdint>

#include "core/xy/gcode/block.hpp"

namespace ap::xy_gcode {

// Position range of the interpreter: |x|, |y|, |z| and arc centres <= 10 m. Keeps every
// coordinate difference below 2^25 um and every squared distance below 2^50, so the arc
// check stays exact in 64-bit (docs/gcode.md §Ranges).
inline constexpr std::int32_t kMaxPositionUm = 10'000'000;

// n / d rounded half away from zero; d > 0. |n| < 2^62 so nothing overflows.
constexpr std::int64_t div_round_half_away(std::int64_t n, std::int64_t d) {
  const std::int64_t q = n / d;  // truncates toward zero
  const std::int64_t r = n % d;  // same sign as n
  const std::int64_t twice = r < 0 ? -2 * r : 2 * r;
  if (twice >= d) return n < 0 ? q - 1 : q + 1;
  return q;
}

// A length word (|v| <= kMaxWordValue, 1e-4 mm or 1e-4 in) in um.
// mm: 1e-4 mm = 0.1 um -> v / 10.  inch: 1 in = 25 400 um exactly, 1e-4 in = 2.54 um -> v * 254 / 100.
// |result| <= 2 539 999 997 (inch), so int64.
constexpr std::int64_t length_um(std::int32_t v, bool inches) {
  return inches ? div_round_half_away(static_cast<std::int64_t>(v) * 254, 100)
                : div_round_half_away(static_cast<std::int64_t>(v), 10);
}

// An F word (1e-4 mm/min or 1e-4 in/min) in um/s.
// mm/min: v * 1e-4 * 1000 / 60 = v / 600.  in/min: v * 1e-4 * 25 400 / 60 = v * 254 / 6000.
// |result| <= 42 333 333 (99999.9999 in/min), fits int32.
constexpr std::int32_t feed_um_s(std::int32_t v, bool inches) {
  return static_cast<std::int32_t>(inches ? div_round_half_away(static_cast<std::int64_t>(v) * 254, 6000)
                                          : div_round_half_away(static_cast<std::int64_t>(v), 600));
}
inline constexpr std::int32_t kMaxFeedUmS = 42'333'333;

}  // namespace ap::xy_gcode
