// Link watchdog (gap G15): the PC repeats its command every 100 ms; three missed periods mean
// the link is gone, and a jog (which only exists while the PC keeps asking) must end.
#pragma once

#include <cstdint>

#include "core/xy/axis/axis.hpp"

namespace ap::xy_axis {

inline constexpr uint16_t kCommandPeriodTicks = 100;                    // 100 ms at the 1 ms tick
inline constexpr uint16_t kLinkTimeoutTicks = 3 * kCommandPeriodTicks;  // 300 ms

// silent: ticks since the last valid command, saturating at kLinkTimeoutTicks. It starts
// expired: nothing may jog before the first command has arrived.
struct LinkWatchdog {
  uint16_t silent = kLinkTimeoutTicks;
};

[[nodiscard]] constexpr LinkWatchdog watchdog_tick(LinkWatchdog w, bool valid_command) {
  if (valid_command) {
    return LinkWatchdog{0};
  }
  return LinkWatchdog{static_cast<uint16_t>(w.silent < kLinkTimeoutTicks ? w.silent + 1 : kLinkTimeoutTicks)};
}

[[nodiscard]] constexpr bool link_alive(LinkWatchdog w) { return w.silent < kLinkTimeoutTicks; }

}  // namespace ap::xy_axis
