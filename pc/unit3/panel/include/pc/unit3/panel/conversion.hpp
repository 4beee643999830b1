// Seed 001's PC program (seed-001.md §7): a displacement typed in millimetres turned into the
// move the unit can make nearest to it. Per axis, in the axis's step mode (0 full step .. 5
// 1/32) and thread (the pitch table of core/unit3/axis, docs/unit3.md):
//   steps = round(|d| / pitch · 200 · 2^mode)   (whole steps of the mode; half rounds up)
//   count = steps · (32 >> mode)                (1/32-step counts, what `X…;` carries)
// The sign of d goes in the `D` line. Integer arithmetic: d in µm, |d| <= 999 999 µm (the
// panel's field, docs/panel.md), so |d| · 200 · 32 < 2^33.
#pragma once

#include <cstdint>
#include <string>

namespace ap::unit3_panel {

inline constexpr std::int64_t kMaxDisplacementUm = 999'999;

struct Conversion {
  bool ok = false;
  std::string error;           // why not (a mode, thread or displacement out of range)
  std::int8_t sign = 1;        // +1 or -1 (+1 for 0)
  std::uint64_t steps = 0;     // whole steps of the mode
  std::uint64_t count = 0;     // 1/32-step counts
  std::int64_t achieved_um = 0;  // the position the move reaches, signed, rounded to µm
};

Conversion to_counts(std::int64_t displacement_um, std::uint8_t mode, std::uint8_t thread);

}  // namespace ap::unit3_panel
