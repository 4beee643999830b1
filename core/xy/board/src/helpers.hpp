// Two one-liners several of the board's source files share: the clamp of a 64-bit value into
// an int32 wire field (a position in µm, a parameter's value) and "the axis is moving". A
// private header of core/xy/board/src, not part of the board's interface.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>

#include "core/xy/axis/axis.hpp"

namespace ap::xy_board {

constexpr std::int32_t clamp32(std::int64_t v) {
  return static_cast<std::int32_t>(std::clamp<std::int64_t>(v, std::numeric_limits<std::int32_t>::min(),
                                                             std::numeric_limits<std::int32_t>::max()));
}

inline bool moving(const xy_axis::State& s) { return s.phase != xy_axis::Phase::Stop; }

}  // namespace ap::xy_board
