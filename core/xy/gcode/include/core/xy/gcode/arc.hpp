// Arc end-point check (docs/gcode.md §Arcs): do the start and end radii of a G2/G3 move
// differ by more than grbl's tolerance? Exact integer arithmetic, no sqrt.
#pragma once

#include <cstdint>

namespace ap::xy_gcode {

// Squared radii in um^2, each < 2^51 (coordinates within +-kMaxPositionUm).
// grbl's rule (gcode.c, arc target check): with d = |r_end - r_start| and r = r_start,
// reject when d > 5 um AND (d > 500 um OR d > 0.001 r); i.e. the tolerance is
// max(5 um, min(500 um, 0.1 % of r)).
bool radius_mismatch(std::uint64_t r2_start, std::uint64_t r2_end);

// sqrt(b) - sqrt(a) > t, exactly (a, b < 2^51, t <= 1000). Exposed for the tests.
bool sqrt_gap_exceeds(std::uint64_t a, std::uint64_t b, std::uint64_t t);

}  // namespace ap::xy_gcode
