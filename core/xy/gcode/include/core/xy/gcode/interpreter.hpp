// Modal G-code interpreter: turns parsed Blocks into Moves in micrometres
// (docs/gcode.md §Interpreter). State: motion mode (none until set), G90 (default) / G91,
// G21 (default) / G20, feed (0 = never set), position (um, starts at 0,0,0), plane G17 only
// (G18/G19 never reach it: the parser rejects them as UnsupportedG).
// On any error apply() changes nothing.
#pragma once

#include <array>
#include <cstdint>

#include "core/xy/gcode/block.hpp"
#include "core/xy/gcode/error.hpp"
#include "core/xy/gcode/units.hpp"

namespace ap::xy_gcode {

enum class MoveKind : std::uint8_t { None /*no motion on this line*/, Rapid, Linear, ArcCw, ArcCcw };

// Coordinates: |from[i]|, |to[i]|, |centre_*| <= kMaxPositionUm (um).
struct Move {
  MoveKind kind = MoveKind::None;
  std::array<std::int32_t, 3> from{};  // x, y, z before the line (None: the current position)
  std::array<std::int32_t, 3> to{};    // x, y, z after the line (None: == from)
  std::int32_t centre_x = 0;           // arcs only: absolute centre (start + I, start + J)
  std::int32_t centre_y = 0;
  std::int32_t feed_um_s = 0;          // Linear/arcs: modal feed, 1..kMaxFeedUmS, 0 = never set;
                                       // Rapid and None: 0 (F does not apply to G0)
  std::uint32_t line = 0;              // the Block's line number (1-based file line)
  std::int32_t n = -1;                 // the N word, -1 without one
  bool z_only = false;                 // Rapid/Linear with no XY motion (thesis N02, N07)

  bool operator==(const Move&) const = default;
};

struct State {
  Motion motion = Motion::None;
  bool incremental = false;             // G91
  bool inches = false;                  // G20
  std::int32_t feed_um_s = 0;           // 0 = never set, else 1..kMaxFeedUmS
  std::array<std::int32_t, 3> pos{};    // um, |pos[i]| <= kMaxPositionUm

  bool operator==(const State&) const = default;
};

struct StepResult {
  Move move;
  Error error;
};

class Interpreter {
 public:
  // Executes one Block: modal words first (G20/G21, G90/G91, G17, F in the line's units,
  // motion mode), then the motion. On error: error set, move default, state unchanged.
  StepResult apply(const Block& block);

  const State& state() const { return state_; }

 private:
  State state_{};
};

}  // namespace ap::xy_gcode
