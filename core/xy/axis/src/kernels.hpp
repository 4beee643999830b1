// The braking kernel step() calls besides the public stop_distance_fine() (kernels.cpp). A
// private header of core/xy/axis/src, not part of the axis's interface.
#pragma once

#include <cstdint>

namespace ap::xy_axis {

// The highest speed in [lo, hi] from which the axis can still stop before the bound, or `lo`
// if none can (kernels.cpp has the derivation and the ranges).
int32_t best_fit(int32_t lo, int32_t hi, int64_t room, int32_t s_fine, int32_t accel);

}  // namespace ap::xy_axis
