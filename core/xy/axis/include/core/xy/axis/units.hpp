// Wire units (um, um/s, um/s^2; gap G4) <-> core units (usteps, usteps/s, usteps/s^2).
//
// usteps = um * steps_per_rev * microsteps / pitch_um. Ranges: pitch_um in [1, 100000],
// steps_per_rev in [1, 1000], microsteps in [1, 256] -> usteps/rev <= 256000; wire values
// are int32, so um * usteps/rev < 2^31 * 2^18 = 2^49: all products are int64.
// Rounding: targets and speeds round to nearest (half away from zero); travel limits round
// inward (min up, max down) so a limit in usteps never lies outside the limit in um; a target
// inside the um limits that rounds past a ustep limit is pulled back onto it. Hence no target
// ever lands past a travel limit.
#pragma once

#include <cstdint>

#include "core/xy/axis/axis.hpp"

namespace ap::xy_axis {

struct Mechanics {
  int32_t pitch_um = 2000;      // lead per revolution; not given in the thesis (G10): 2 mm
  int32_t steps_per_rev = 200;  // 1.8 deg motor (Tab. 4-1)
  int32_t microsteps = 16;
};

enum class Round : uint8_t { Nearest, Down, Up };

struct Converted {
  int32_t value = 0;
  Error error = Error::None;
};

[[nodiscard]] constexpr bool mechanics_valid(const Mechanics& m) {
  return m.pitch_um >= 1 && m.pitch_um <= 100'000 && m.steps_per_rev >= 1 && m.steps_per_rev <= 1000 &&
         m.microsteps >= 1 && m.microsteps <= 256;
}

[[nodiscard]] constexpr int64_t usteps_per_rev(const Mechanics& m) {
  return static_cast<int64_t>(m.steps_per_rev) * m.microsteps;
}

namespace detail {
// n / d rounded as asked, d > 0, exact for negative n too.
[[nodiscard]] constexpr int64_t div_round(int64_t n, int64_t d, Round r) {
  const int64_t q = n / d;
  const int64_t rem = n % d;
  switch (r) {
    case Round::Down: return rem < 0 ? q - 1 : q;
    case Round::Up: return rem > 0 ? q + 1 : q;
    case Round::Nearest:
    default:
      if (2 * rem >= d) return q + 1;
      if (-2 * rem >= d) return q - 1;
      return q;
  }
}
}  // namespace detail

// um -> usteps, result in [lo, hi] or OutOfLimits.
[[nodiscard]] constexpr Converted um_to_usteps(int32_t um, const Mechanics& m, Round r,
                                               int32_t lo = -kPosMax, int32_t hi = kPosMax) {
  if (!mechanics_valid(m)) {
    return {0, Error::BadConfig};
  }
  const int64_t v = detail::div_round(static_cast<int64_t>(um) * usteps_per_rev(m), m.pitch_um, r);
  if (v < lo || v > hi) {
    return {0, Error::OutOfLimits};
  }
  return {static_cast<int32_t>(v), Error::None};
}

[[nodiscard]] constexpr Converted speed_to_usteps(int32_t um_s, const Mechanics& m) {
  if (um_s < 0) {
    return {0, Error::BadCommand};
  }
  return um_to_usteps(um_s, m, Round::Nearest, 0, kSpeedMax);
}

[[nodiscard]] constexpr Converted accel_to_usteps(int32_t um_s2, const Mechanics& m) {
  if (um_s2 <= 0) {
    return {0, Error::BadCommand};
  }
  return um_to_usteps(um_s2, m, Round::Nearest, 1, kAccelMax);
}

struct UstepLimits {
  int32_t min = 0;
  int32_t max = 0;
  Error error = Error::None;
};

// Travel limits rounded inward; an empty interval is a configuration error.
[[nodiscard]] constexpr UstepLimits limits_to_usteps(int32_t min_um, int32_t max_um, const Mechanics& m) {
  const Converted lo = um_to_usteps(min_um, m, Round::Up);
  const Converted hi = um_to_usteps(max_um, m, Round::Down);
  if (lo.error != Error::None) return {0, 0, lo.error};
  if (hi.error != Error::None) return {0, 0, hi.error};
  if (lo.value >= hi.value) return {0, 0, Error::BadConfig};
  return {lo.value, hi.value, Error::None};
}

// An absolute target in um, checked against the um travel limits, then rounded to nearest and
// kept inside the inward-rounded ustep limits.
[[nodiscard]] constexpr Converted target_to_usteps(int32_t um, int32_t min_um, int32_t max_um, const Mechanics& m) {
  if (um < min_um || um > max_um) {
    return {0, Error::OutOfLimits};
  }
  const UstepLimits lim = limits_to_usteps(min_um, max_um, m);
  if (lim.error != Error::None) {
    return {0, lim.error};
  }
  // Nearest in 64 bits, then the clamp: a target on a limit at the edge of the position range
  // rounds to kPosMax + 1 before the clamp pulls it back onto the (inward-rounded) limit.
  // |um| < 2^31, usteps/rev <= 256000 < 2^18: the product fits int64.
  const int64_t t = detail::div_round(static_cast<int64_t>(um) * usteps_per_rev(m), m.pitch_um, Round::Nearest);
  const int64_t v = t < lim.min ? lim.min : (t > lim.max ? lim.max : t);
  return {static_cast<int32_t>(v), Error::None};
}

// usteps -> um (nearest) for the echo; |usteps| <= 1e9 * pitch 1e5 < 2^63.
[[nodiscard]] constexpr int64_t usteps_to_um(int32_t usteps, const Mechanics& m) {
  return detail::div_round(static_cast<int64_t>(usteps) * m.pitch_um, usteps_per_rev(m), Round::Nearest);
}

}  // namespace ap::xy_axis
