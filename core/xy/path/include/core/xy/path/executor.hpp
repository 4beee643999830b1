// The coordinated XY path on the board (docs/cnc.md "On the board"): a queue of line and arc
// segments in microsteps, grouped into chains that one jerk-limited S-curve runs rest to rest,
// interpolated move by move (core/xy/interp) so both axes arrive together.
//
// Chains [D, docs/cnc.md "Chains"]: consecutive segments whose junction is tangent (the
// look-ahead's turn of exactly 0, core/xy/lookahead) form one chain and keep their speed through
// the junction; any other junction ends the chain at rest. A corner taken at speed makes each
// axis's velocity jump, which a stepper cannot follow (seed-000's start speed is the only jump
// the axis core allows), so the thesis's linear corner law is reported, not used to cross a
// corner at speed. A chain starts once it is closed: the next queued segment is not tangent,
// path_end arrived after its last segment, or the queue is full.
//
// The S-curve runs over moves (interpolation points: one step of the driving axis, seed-003.md
// §5.3.2 "indexed by step"), so each axis's speed is at most the path's move rate: the path's
// v_max is the axes' positioning speed and no axis exceeds it.
//
// Ranges: positions |p| <= xy_axis::kPosMax; one segment's |delta| <= xy_interp::Line::kMaxDelta; a
// chain's moves <= xy_scurve::kMaxMoves (a longer chain is refused when its segment is queued).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/xy/interp/arc.hpp"
#include "core/xy/interp/line.hpp"
#include "core/xy/scurve/profile.hpp"

namespace ap::xy_path {

inline constexpr std::size_t kAxes = 2;
inline constexpr std::size_t kQueue = 16;
// Arc moves counted per control tick before a chain starts (a copy of the arc is walked):
// bounds the tick's extra work to a few hundred microseconds on the Cortex-M4.
inline constexpr std::uint32_t kCountBudget = 4096;

using Point = std::array<std::int32_t, kAxes>;

enum class Kind : std::uint8_t { Line, ArcCw, ArcCcw };

enum class Error : std::uint8_t {
  None,
  QueueFull,          // kQueue segments wait already
  OutOfLimits,        // the segment (for an arc: its swept extremes) leaves the soft limits
  ZeroLength,         // a line to where the queue already ends: nothing to do
  ArcZeroRadius,      // the centre is the start
  ArcRadiusMismatch,  // start and end radius differ by more than max(2 steps, 0.1 %)
  TooLong,            // the segment or its chain is past the documented ranges
  Stopping,           // a stop is in progress: the path takes nothing until it is at rest
  BadLimits,          // the axes' speed, acceleration or the jerk outside scurve's ranges
  // Refusals the board decides before a segment reaches the queue (core/xy/board):
  NotHomed,           // an axis's position is not known
  Busy,               // an axis moves on its own (jog, move, homing) or the board sleeps
  NoCentre,           // an arc without a centre frame before it
  MixedParts,         // one frame's parts disagree (a centre and a segment, a line and an arc)
};
[[nodiscard]] const char* error_name(Error e);

struct Segment {
  Kind kind = Kind::Line;
  Point start{};
  Point end{};
  Point centre{};  // arcs only
};

// The path's limits in moves (docs/cnc.md "Speeds"): v_max = the axes' positioning speed,
// a_max = their acceleration, j_max = the thesis's jerk; soft limits per axis in microsteps.
struct Limits {
  xy_scurve::Limits motion{1, 1, 1};
  Point soft_min{};
  Point soft_max{};
};

enum class Status : std::uint8_t { Idle, Waiting, Running, Stopping };

// What one tick does to the axes: `steps` STEP pulses per axis, all in `dir`.
struct TickOut {
  std::array<std::int8_t, kAxes> dir{1, 1};
  std::array<std::int32_t, kAxes> steps{};
  // Each axis's speed along the path in 1/1000 usteps/s (xy_axis::State::v units): the move rate
  // times the axis's share of the tangent (docs/cnc.md "Axis speeds").
  std::array<std::int32_t, kAxes> v_fine{};
  bool finished_chain = false;  // the last chain move was made this tick and the profile is at rest
};

// Inputs of one tick the path must obey.
struct TickIn {
  std::array<bool, kAxes> toward_min_blocked{};  // a min endstop active or not yet left
  std::array<bool, kAxes> toward_max_blocked{};
};

enum class Halt : std::uint8_t { None, Endstop };

class Executor {
 public:
  // Queues a segment starting where the queue ends (the first one starts at `from`). On an
  // error nothing changes.
  Error add(const Segment& s, const Limits& lim);
  // path_end: the last queued segment ends at rest (closes its chain).
  void close();
  // A controlled, jerk-limited stop along the path; the queue behind it is dropped.
  void stop();
  // Drops everything at once (the caller stops the axes: endstop, fault).
  void clear();

  // One control tick. `pos` is the axes' step counter, advanced here by the moves made.
  TickOut tick(const TickIn& in, Point& pos, Halt& halt);

  [[nodiscard]] Status status() const { return status_; }
  [[nodiscard]] bool active() const { return count_ > 0 || status_ != Status::Idle; }
  [[nodiscard]] std::size_t queued() const { return count_; }
  // Where the queue ends (the start of the next segment) when it holds any.
  [[nodiscard]] Point queue_end() const;
  // The running chain's exact kinematics (1/1000 moves per s, s^2, s^3), for traces.
  [[nodiscard]] xy_scurve::Kinematics kinematics() const;
  [[nodiscard]] const xy_scurve::Plan& plan() const { return plan_; }
  // The profile's segment 0..6 (7 at rest): accelerating 0-2, cruising 3, decelerating 4-6.
  [[nodiscard]] std::uint8_t profile_segment() const { return prof_.seg; }
  [[nodiscard]] bool stopping() const { return status_ == Status::Stopping; }

 private:
  struct Queued {
    Segment seg{};
    std::uint32_t moves = 0;       // known for lines at once, for arcs after counting
    bool counted = false;
    bool tangent_next = false;     // the junction to the next queued segment is tangent
    xy_scurve::Limits motion{1, 1, 1};  // the limits in force when it was queued (arcs: capped)
  };
  // One segment being walked move by move.
  struct Cursor {
    Kind kind = Kind::Line;
    xy_interp::Line line{};
    xy_interp::Arc arc{};
    Point origin{};  // line: its start; arc: its centre
    Point delta{};   // line: end - start
    [[nodiscard]] bool done() const;
    [[nodiscard]] std::array<std::int8_t, kAxes> peek() const;
    void advance();
    [[nodiscard]] Point tangent(const Point& pos) const;
  };

  Queued& at(std::size_t k) { return q_[(head_ + k) % kQueue]; }
  const Queued& at(std::size_t k) const { return q_[(head_ + k) % kQueue]; }
  [[nodiscard]] std::size_t chain_length() const;  // segments of the chain at the head
  [[nodiscard]] bool chain_closed(std::size_t n) const;
  bool count_arcs(std::size_t n);                  // true once every arc of the chain is counted
  void start_chain(std::size_t n);
  void open_cursor();
  void finish_chain();

  std::array<Queued, kQueue> q_{};
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  bool closed_ = false;  // path_end after the last queued segment
  std::uint64_t open_bound_ = 0;  // a bound of the moves of the chain the last queued segment ends
  Status status_ = Status::Idle;
  std::array<std::int8_t, kAxes> last_dir_{1, 1};

  // The running chain.
  std::size_t chain_n_ = 0;
  std::size_t chain_seg_ = 0;  // index in the chain of the segment the cursor walks
  std::uint32_t chain_moves_ = 0;
  std::uint32_t done_ = 0;     // moves made in the chain
  xy_scurve::Plan plan_{};
  xy_scurve::State prof_{};
  Cursor cur_{};
  // The counting copy of an arc.
  bool counting_ = false;
  std::size_t counting_k_ = 0;
  xy_interp::Arc count_arc_{};
  std::uint32_t count_n_ = 0;
};

}  // namespace ap::xy_path
