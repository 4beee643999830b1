// seed-001.md §7's send logic (conversion.hpp).
#include "pc/unit3/panel/conversion.hpp"

#include "core/unit3/axis/counting.hpp"
#include "protocol/unit3/wire/dialect.hpp"

namespace ap::unit3_panel {

Conversion to_counts(std::int64_t um, std::uint8_t mode, std::uint8_t thread) {
  Conversion c;
  if (mode > unit3_wire::kMaxModeDigit) {
    c.error = "step mode " + std::to_string(mode) + " outside 0..5";
    return c;
  }
  if (thread >= unit3_axis::kThreads) {
    c.error = "thread " + std::to_string(thread) + " outside 0..6";
    return c;
  }
  if (um < -kMaxDisplacementUm || um > kMaxDisplacementUm) {
    c.error = "displacement " + std::to_string(um) + " um outside +-" + std::to_string(kMaxDisplacementUm) + " um";
    return c;
  }
  const std::uint64_t pitch = unit3_axis::kThreadTable[thread].pitch_um;
  const std::uint64_t mag = static_cast<std::uint64_t>(um < 0 ? -um : um);
  const std::uint64_t per_rev = static_cast<std::uint64_t>(unit3_axis::kStepsPerRev) << mode;  // steps of the mode
  c.sign = um < 0 ? std::int8_t{-1} : std::int8_t{1};
  c.steps = (mag * per_rev + pitch / 2) / pitch;
  c.count = c.steps * unit3_axis::counts_per_pulse(mode);
  c.achieved_um = unit3_axis::position_um(c.sign * static_cast<std::int64_t>(c.count), thread);
  c.ok = true;
  return c;
}

}  // namespace ap::unit3_panel
