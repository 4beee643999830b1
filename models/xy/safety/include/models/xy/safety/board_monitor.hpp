// The axis safety properties of a running board core (docs/board.md "Safety properties"),
// checked after every tick from what the board shows (axis states, motor outputs, sampled
// inputs, counters), not from how it decides:
//   - every axis state inside its invariant ranges; DIR changes only at or below the start
//     speed; no step against the DIR state;
//   - no step toward an active endstop, nor toward one not yet moved away from;
//   - blocked: the speed never rises, and once stopped not one step until unblocked;
//   - soft travel limits never crossed once the position is known;
//   - no jog outlives three silent command periods (frames that feed the watchdog: run, or a
//     repeat of the last one taken, docs/protocol.md "Delivery");
//   - a target set from rest is never passed (no overshoot);
//   - no step while the saved step counter is marked valid;
//   - the coordinated path (docs/cnc.md "Safety properties"): no axis steps faster than the
//     path's v_max allows, a stopping path never speeds up, a path that ends without a stop
//     ends exactly where its last segment ends.
// Used by the board fuzz target (aborts on the first) and the simulated board (reports them).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/xy/axis/axis.hpp"
#include "core/xy/board/board.hpp"

namespace ap::model::xy_safety {

struct Violation {
  std::uint32_t tick = 0;  // the board's tick count after the tick
  int axis = -1;           // 0 = X, 1 = Y, -1 = the board
  const char* what = "";
};

class BoardMonitor {
 public:
  // After boot() of a (new) board: endstops active at power-up count as latched.
  void booted(const xy_board::Board& b);
  // Right before board.tick().
  void before_tick(const xy_board::Board& b);
  // Right after it: appends this tick's violations.
  void after_tick(const xy_board::Board& b, std::vector<Violation>& out);

 private:
  struct AxisWatch {
    bool latch_min = false;
    bool latch_max = false;
    bool blocked_stopped = false;
    bool tracking = false;  // a move started from rest toward `target`
    std::int32_t target = 0;
    int side = 0;
  };
  void check_axis(const xy_board::Board& b, std::size_t a, bool mech_changed, std::vector<Violation>& out);

  std::array<AxisWatch, xy_board::kAxes> w_{};
  std::array<xy_axis::State, xy_board::kAxes> before_{};
  xy_axis::Mechanics mech_{};
  std::uint32_t silent_ = xy_axis::kLinkTimeoutTicks;
  std::uint32_t fed_ = 0;
  // The path as seen before the tick.
  bool path_active_ = false;
  bool path_stopping_ = false;
  std::int64_t path_vel_ = 0;
  std::int64_t path_acc_ = 0;
  std::array<std::int32_t, xy_board::kAxes> path_end_{};
  void check_path(const xy_board::Board& b, std::vector<Violation>& out);
};

}  // namespace ap::model::xy_safety
