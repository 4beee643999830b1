// One-liners several of the board's source files share: the clamp of a 64-bit value into an
// int32 wire field (a position in µm, a parameter's value), "the axis is moving" and "the axis
// holds a motion". A private header of core/xy/board/src, not part of the board's interface.
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

// Moving, or holding a motion that steps again: a jog held at its reversal stop or at a soft
// limit, a move standing short of its target. A move standing on its target is finished
// (REACHED; the axis core drops it on the next tick, edge I) and holds nothing, so a command
// that needs the axis at rest is not refused in that tick (docs/echo-model.md "Decisions").
inline bool holds_motion(const xy_axis::State& s) {
  const bool finished = s.mode == xy_axis::Mode::Position && s.pos == s.target;
  return moving(s) || (s.mode != xy_axis::Mode::Idle && !finished);
}

}  // namespace ap::xy_board
