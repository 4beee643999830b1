// An independent checker of docs/cnc.md's chain rules for the coordinated XY path, written from
// docs/cnc.md ("Chains", "Speeds", "Refusals") and seed-003.md where the docs cite it, never from
// core/path. Floating point; never code under test.
//
// It observes the path from outside, the way a PC and a logic analyser would:
//   - the segments the PC submitted and the board accepted, the QueueFull refusals, path_end;
//   - after every 1 ms control tick: both axes' step counters and both axes' reported speeds
//     (xy_axis::State::v, 1/1000 steps/s) and the STEP pulses of the tick.
// The path's speed is the move rate: the driving axis makes one step per move and its speed is
// the move rate (docs/cnc.md "Speeds", "Axis speeds"), so it is the larger reported axis speed.
//
// Rules (each violation names its rule; docs/cnc.md sections in quotes):
//   cap.segment   the speed at a tick's end never exceeds the cap of the segment the carriage is
//                 on: a line's is v_max (the axes' `fast`, at most 100 000 moves/s; F is
//                 ignored, "Speeds" [T seed-003.md §2.5]); an arc's is min(v_max, sqrt(a_max r)),
//                 r its radius in steps ("Speeds" [D]);
//   cap.join      a tick that crosses a join (a line into an arc, an arc into a line or an arc)
//                 runs, at both its ends, within every crossed segment's cap plus one tick of
//                 acceleration: the speed at the join itself is within both caps;
//   cap.chain     between two rests the speed never exceeds the lowest cap of every segment run
//                 in between ("Speeds": on an arc "the chain's v_max is further capped");
//   cap.steps     the same caps from the step counters alone: the moves of a window of ticks
//                 (at least the Chebyshev distance per tick) fit the caps' integral, + 2 moves
//                 (the whole-move floor and one tick of reversal lag, "Axis speeds");
//   cap.centripetal  on an arc, v_e^2 / r <= 2 a_max, v_e the Euclidean speed from the axis
//                 speeds (each axis is at most the move rate, so v_e <= sqrt(2) x the move rate;
//                 docs/cnc.md "Speeds" states what the cap means in millimetres);
//   path.on       every position lies on a submitted segment, in order (a raster point is within
//                 1/2 step of its line or circle, docs/interpolation.md; seed-003.md §3.2, §3.3);
//   corner.rest   a junction that is not tangent, or that a path_end closes, is passed at rest:
//                 the carriage stands at the junction with speed 0 ("Chains": "Any other junction
//                 ends the chain at rest");
//   tangent.kept  a tangent junction is crossed at speed unless its chain was cut there (the queue
//                 full with the chain still open, or 2^20 moves) ("Chains": "the speed is kept
//                 through the junction");
//   rest.inside   the path comes to rest only at the end of a segment (no stop in the middle of
//                 a chain; the checker is not used across `stop`s);
//   start.open    a chain does not start before it is closed ("Chains": "A chain starts once it
//                 is closed");
//   live.start    a closed chain starts within ceil(its arcs' move bounds / 4096) + 2 ticks plus
//                 the S-curve's first ticks below 1/1000 move/s ("Chains": closed by a
//                 non-tangent segment, path_end, or the queue full; arcs counted at most 4096
//                 moves per tick). With the queue full of one open tangent chain the chain must
//                 start: a PC that waits for queue space before it sends the chain's end would
//                 otherwise wait for ever;
//   live.space    a PC refused with QueueFull is accepted within the bound of the head chain's
//                 start and run (its S-curve at the chain's cap);
//   live.end      after path_end the path is at rest at its last segment's end within the sum,
//                 over the chains still to run, of each chain's start bound and its S-curve's
//                 time at the chain's lowest cap ("Chains", "Speeds": one S-curve per chain at
//                 its segments' lowest limits). A small arc in a long tangent chain holds the
//                 whole chain at its cap, so a contour may rightly take many minutes;
//   queue.full    QueueFull only when 16 segments wait ("Refusals"; a segment waits until its
//                 chain has run to rest, docs/echo-model.md "queued").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ap::model::xy_cnc_rules {

using Point = std::array<std::int64_t, 2>;  // steps

enum class Kind : std::uint8_t { Line, ArcCw, ArcCcw };

struct Segment {
  Kind kind = Kind::Line;
  Point start{};
  Point end{};
  Point centre{};  // arcs only
};

struct Config {
  double v_max = 1;            // moves/s: the axes' positioning speed (the slower `fast`)
  double a_max = 1;            // moves/s^2: the axes' acceleration (the smaller)
  double j_max = 1;            // moves/s^3: the thesis's J in microsteps (seed-003.md §5.3.1)
  std::size_t queue = 16;      // docs/cnc.md "Refusals": 16 segments wait already
  double count_budget = 4096;  // docs/cnc.md "Chains": arcs counted at most 4096 moves a tick
  std::uint64_t max_chain_moves = std::uint64_t{1} << 20;  // docs/cnc.md "Refusals", TooLong
  std::size_t window = 50;                                 // ticks of the cap.steps window
};

struct Violation {
  std::uint64_t tick = 0;
  std::string rule;
  std::string what;
};

// ---- the docs' quantities ------------------------------------------------------------------

// The segment's own speed cap in moves/s (docs/cnc.md "Speeds").
[[nodiscard]] double segment_cap(const Config& c, const Segment& s);
// The radius of an arc in steps (its start's distance from the centre).
[[nodiscard]] double arc_radius(const Segment& s);
// Direction of motion where the segment starts / ends (a line's delta; an arc's tangent,
// perpendicular to the radius in its turning sense).
[[nodiscard]] Point entry_direction(const Segment& s);
[[nodiscard]] Point exit_direction(const Segment& s);
// docs/cnc.md "Chains": tangent = exactly parallel in the same sense (integer cross product 0,
// dot product > 0).
[[nodiscard]] bool tangent(const Segment& in, const Segment& out);
// docs/cnc.md "Refusals" (TooLong): a line makes max(|dx|, |dy|) moves; an arc at most
// (r + 2) * 5794 / 1024 + 2 |r_s - r_e| + 32, radii in steps rounded down.
[[nodiscard]] std::uint64_t moves_bound(const Segment& s);
// Ticks an S-curve over `moves` at (v, a_max, j_max) takes at most: twice the continuous
// rest-to-rest minimum (seed-003.md §5.4) at the longer of `moves` and the distance that
// reaches v, plus the whole-tick rounding (docs/scurve.md "Planning"), plus 50 ticks.
[[nodiscard]] std::uint64_t chain_ticks_bound(const Config& c, double moves, double v);
// Ticks from rest until a profile's speed shows at least 1/1000 move/s (its first jerk ticks;
// the profile's jerk is at least J/8, docs/scurve.md "Planning": sigma and the rounded-up ramp).
[[nodiscard]] std::uint64_t creep_ticks(const Config& c);

// Is p on the segment (within the raster's bounds)?
[[nodiscard]] bool on_segment(const Segment& s, const Point& p);

// ---- the checker -----------------------------------------------------------------------------

class ChainChecker {
 public:
  ChainChecker(const Config& c, const Point& at);

  // The PC's side, in the order the board takes them, before the tick they precede.
  void accepted(const Segment& s);
  void refused_queue_full();
  void path_end();

  // One control tick's outcome: the step counters after it, each axis's reported speed
  // (1/1000 steps/s) and its STEP pulses in the tick.
  void tick(const Point& pos, const std::array<std::int64_t, 2>& v_fine, const std::array<std::int32_t, 2>& steps);

  // The run is over (the board at rest, the PC done): the end and the last window.
  void finish();

  [[nodiscard]] const std::vector<Violation>& violations() const { return violations_; }
  [[nodiscard]] bool ok() const { return violations_.empty(); }
  [[nodiscard]] std::string report() const;  // the first violations, one a line

  // Measurements.
  [[nodiscard]] std::uint64_t ticks() const { return tick_; }
  [[nodiscard]] std::uint64_t first_motion_tick() const { return first_motion_; }  // ~0: none
  [[nodiscard]] bool path_end_sent() const { return end_sent_; }
  [[nodiscard]] std::uint64_t path_end_tick() const { return end_tick_; }
  // The tick by which the path must be at rest at its end (live.end); ~0 before path_end.
  [[nodiscard]] std::uint64_t end_deadline() const { return end_deadline_; }
  [[nodiscard]] double max_arc_speed_over_cap() const { return max_arc_ratio_; }
  [[nodiscard]] std::size_t rests() const { return rests_; }

 private:
  struct Tick {
    double v = 0;          // move rate at the tick's end, moves/s
    double allowance = 0;  // the lowest cap of the segments run in the tick, moves/s
    double cheb = 0;       // Chebyshev distance moved in the tick (a lower bound of its moves)
  };

  void fail(const std::string& rule, const std::string& what);
  [[nodiscard]] std::size_t head_chain_end() const;  // last index of the chain at freed_
  [[nodiscard]] bool head_closed(std::string* why) const;
  [[nodiscard]] std::uint64_t start_bound(std::size_t from, std::size_t to) const;
  [[nodiscard]] std::uint64_t remaining_ticks_bound() const;  // the chains from freed_ on
  void check_window();

  Config c_;
  std::vector<Segment> segs_;
  std::vector<double> caps_;
  std::vector<bool> chain_next_;  // the junction after segment k continues its chain
  std::vector<bool> cut_next_;    // the chain may be cut after segment k (queue full, length)
  std::vector<bool> end_after_;   // a path_end came after segment k
  std::uint64_t open_moves_ = 0;  // moves bound of the open chain the last segment ends
  bool end_sent_ = false;
  std::uint64_t end_tick_ = ~std::uint64_t{0};
  std::uint64_t end_deadline_ = ~std::uint64_t{0};
  bool end_reported_ = false;

  std::size_t freed_ = 0;  // segments whose chain has run to rest
  std::size_t cur_ = 0;    // the segment the carriage is on
  Point pos_{};
  double v_prev_ = 0;
  bool moving_ = false;       // since the last rest
  bool rest_at_end_ = false;  // standing where the last chain ended
  bool entered_ = false;      // the carriage has moved onto segment cur_
  bool has_prev_tick_ = false;
  double episode_max_v_ = 0;
  double episode_min_cap_ = 0;
  std::uint64_t episode_max_tick_ = 0;

  std::uint64_t tick_ = 0;
  std::uint64_t first_motion_ = ~std::uint64_t{0};
  std::uint64_t idle_ = 0;  // ticks standing with a closed head chain
  bool live_reported_ = false;
  bool waiting_ = false;
  std::uint64_t wait_since_ = 0;
  std::uint64_t wait_bound_ = 0;
  bool wait_reported_ = false;
  std::uint64_t longest_wait_ = 0;
  double max_centripetal_ = 0;
  double max_arc_ratio_ = 0;
  std::size_t rests_ = 0;

  std::vector<Tick> ticks_;
  std::vector<Violation> violations_;
};

}  // namespace ap::model::xy_cnc_rules
