// A segment's way into the queue (Executor::add), apart from the running chain because it
// decides, before anything moves, what the path will take: the refusals of docs/cnc.md
// "Refusals" (the soft limits, for an arc its swept extremes; zero length; an arc's radius;
// the ranges and move bounds; the S-curve's limits; a full queue; a running stop), the arc's
// speed cap (docs/cnc.md "Speeds") and the tangent junction that chains it to the segment
// before it (docs/cnc.md "Chains"). Also the refusals' names. executor.cpp runs the chains.
#include "core/xy/path/executor.hpp"

#include "core/xy/lookahead/junction.hpp"

#include "points.hpp"

namespace ap::xy_path {

namespace {

xy_lookahead::Turn la_turn(Kind k) { return k == Kind::ArcCw ? xy_lookahead::Turn::Cw : xy_lookahead::Turn::Ccw; }

// The segment's direction where it starts and where it ends (the look-ahead's inputs).
xy_lookahead::Direction entry_direction(const Segment& s) {
  if (s.kind == Kind::Line) return xy_lookahead::line_direction(s.end[0] - s.start[0], s.end[1] - s.start[1], 0);
  const auto r = rel(s.start, s.centre);
  return xy_lookahead::arc_start_direction(r[0], r[1], la_turn(s.kind));
}

xy_lookahead::Direction exit_direction(const Segment& s) {
  if (s.kind == Kind::Line) return xy_lookahead::line_direction(s.end[0] - s.start[0], s.end[1] - s.start[1], 0);
  const auto r = rel(s.end, s.centre);
  return xy_lookahead::arc_end_direction(r[0], r[1], la_turn(s.kind));
}

// Is the direction `d` (a unit axis vector) inside the counter-clockwise sweep from S to E?
// An E on S's ray is a full circle (xy_interp::Arc's rule). Angles are compared without atan:
// first by the half plane on S's left (angle in [0, 180)), then by the cross product, which
// orders two directions of one half plane (docs/cnc.md "Limits").
bool ccw_sweep_holds(std::array<std::int64_t, 2> s, std::array<std::int64_t, 2> e, std::array<std::int64_t, 2> d) {
  const auto cross = [](std::array<std::int64_t, 2> a, std::array<std::int64_t, 2> b) { return a[0] * b[1] - a[1] * b[0]; };
  const auto dot = [](std::array<std::int64_t, 2> a, std::array<std::int64_t, 2> b) { return a[0] * b[0] + a[1] * b[1]; };
  const std::int64_t se = cross(s, e);
  if (se == 0 && dot(s, e) > 0) return true;  // full circle
  const auto half = [&](std::array<std::int64_t, 2> v) {
    const std::int64_t c = cross(s, v);
    return (c > 0 || (c == 0 && dot(s, v) > 0)) ? 0 : 1;
  };
  const int hd = half(d);
  const int he = half(e);
  if (hd != he) return hd < he;
  return cross(d, e) >= 0;  // e at or beyond d
}

// The largest |coordinate - centre| an arc's raster can reach: every circle point lies within
// 1/2 step of the circle of radius R (xy_interp::Arc), so an integer coordinate k along an axis
// satisfies k - 1/2 < R, i.e. (2k - 1)^2 < 4 R^2; the tail runs between a circle point and the
// end, inside both. Exact at the circle's own extremes (a start on the soft limit passes).
std::int64_t arc_reach(std::int64_t r2_start, std::int64_t r2_end) {
  const std::int64_t r2 = r2_start > r2_end ? r2_start : r2_end;
  std::int64_t k = xy_interp::isqrt64(static_cast<std::uint64_t>(r2));
  if ((2 * k + 1) * (2 * k + 1) < 4 * r2) ++k;  // 4 r2 < 2^43: no overflow
  return k;
}

bool inside(std::int64_t v, std::int32_t lo, std::int32_t hi) { return v >= lo && v <= hi; }

// Upper bound of an arc's moves: a circle of radius r takes 8 r / sqrt(2) moves (one driving
// step per move in each octant, seed-003.md §3.3), plus the tail (< |r_end - r_start| + 2 per
// axis) — 5794/1024 > 4 sqrt(2). Tested against counted arcs in properties/path.
std::uint64_t arc_moves_bound(std::int64_t r2_start, std::int64_t r2_end) {
  const std::uint64_t rs = xy_interp::isqrt64(static_cast<std::uint64_t>(r2_start));
  const std::uint64_t re = xy_interp::isqrt64(static_cast<std::uint64_t>(r2_end));
  const std::uint64_t dr = rs > re ? rs - re : re - rs;
  return (rs + 2) * 5794U / 1024U + 2 * dr + 32;
}

}  // namespace

const char* error_name(Error e) {
  switch (e) {
    case Error::None: return "none";
    case Error::QueueFull: return "queue full";
    case Error::OutOfLimits: return "out of the soft limits";
    case Error::ZeroLength: return "zero length";
    case Error::ArcZeroRadius: return "arc of zero radius";
    case Error::ArcRadiusMismatch: return "arc end not on its circle";
    case Error::TooLong: return "too long";
    case Error::Stopping: return "stopping";
    case Error::BadLimits: return "speed, acceleration or jerk outside the profile's ranges";
    case Error::NotHomed: return "position not known";
    case Error::Busy: return "an axis is busy";
    case Error::NoCentre: return "arc without a centre";
    case Error::MixedParts: return "the frame's parts disagree";
  }
  return "?";
}

Point Executor::queue_end() const { return count_ == 0 ? Point{} : at(count_ - 1).seg.end; }

Error Executor::add(const Segment& s, const Limits& lim) {
  if (status_ == Status::Stopping) return Error::Stopping;
  if (count_ == kQueue) return Error::QueueFull;
  // The end must lie inside the soft limits, the start need not: a carriage that stands outside
  // (an encoder start below the minimum) may move back in (docs/cnc.md "Refusals").
  for (std::size_t a = 0; a < kAxes; ++a) {
    if (!inside(s.end[a], lim.soft_min[a], lim.soft_max[a])) return Error::OutOfLimits;
  }
  Queued q;
  q.seg = s;
  std::uint64_t bound = 0;
  if (s.kind == Kind::Line) {
    const std::array<std::int32_t, 3> d{s.end[0] - s.start[0], s.end[1] - s.start[1], 0};
    if (d[0] == 0 && d[1] == 0) return Error::ZeroLength;
    if (!xy_interp::Line::valid(d)) return Error::TooLong;
    q.moves = xy_interp::Line(d).moves();
    q.counted = true;
    bound = q.moves;
  } else {
    const auto rs = rel(s.start, s.centre);
    const auto re = rel(s.end, s.centre);
    if (!xy_interp::Arc::in_range(rs) || !xy_interp::Arc::in_range(re)) return Error::TooLong;
    const std::int64_t r2s = std::int64_t{rs[0]} * rs[0] + std::int64_t{rs[1]} * rs[1];
    const std::int64_t r2e = std::int64_t{re[0]} * re[0] + std::int64_t{re[1]} * re[1];
    if (r2s == 0 || r2e == 0) return Error::ArcZeroRadius;
    // docs/cnc.md "Arcs": the end may miss the circle by the rounding of the G-code's
    // micrometres, not more: max(2 steps, 0.1 % of the radius) (grbl's rule in steps).
    const std::int64_t rsi = xy_interp::isqrt64(static_cast<std::uint64_t>(r2s));
    const std::int64_t rei = xy_interp::isqrt64(static_cast<std::uint64_t>(r2e));
    const std::int64_t tol = rsi / 1000 > 2 ? rsi / 1000 : 2;
    if (abs64(rsi - rei) > tol) return Error::ArcRadiusMismatch;
    // The sweep's extremes: every axis direction the arc passes must stay inside the limits.
    const std::int64_t reach = arc_reach(r2s, r2e);
    std::array<std::int64_t, 2> s64{rs[0], rs[1]};
    std::array<std::int64_t, 2> e64{re[0], re[1]};
    if (s.kind == Kind::ArcCw) {  // a clockwise sweep is a counter-clockwise one mirrored in y
      s64[1] = -s64[1];
      e64[1] = -e64[1];
    }
    constexpr std::array<std::array<std::int64_t, 2>, 4> kAxisDirs{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
    for (const auto& d : kAxisDirs) {
      std::array<std::int64_t, 2> dm = d;
      if (s.kind == Kind::ArcCw) dm[1] = -dm[1];
      if (!ccw_sweep_holds(s64, e64, dm)) continue;
      const std::int64_t px = s.centre[0] + d[0] * reach;
      const std::int64_t py = s.centre[1] + d[1] * reach;
      if ((d[0] != 0 && !inside(px, lim.soft_min[0], lim.soft_max[0])) ||
          (d[1] != 0 && !inside(py, lim.soft_min[1], lim.soft_max[1]))) {
        return Error::OutOfLimits;
      }
    }
    const xy_interp::ArcResult ar = xy_interp::Arc::make(rs, re, s.kind == Kind::ArcCw ? xy_interp::Turn::Cw : xy_interp::Turn::Ccw);
    if (ar.error != xy_interp::Error::None) return Error::TooLong;
    bound = arc_moves_bound(r2s, r2e);
  }
  if (bound > xy_scurve::kMaxMoves) return Error::TooLong;
  if (xy_scurve::plan(1, lim.motion).error != xy_scurve::Error::None) return Error::BadLimits;
  q.motion = lim.motion;
  if (s.kind != Kind::Line) {
    // docs/cnc.md "Speeds": on an arc of radius r (steps) the centripetal acceleration v^2 / r
    // stays within a_max. v is counted in moves/s, and a move is up to sqrt(2) steps long (at
    // 45 deg both axes step), so the move rate is capped at sqrt(a_max r / 2).
    const auto rs = rel(s.start, s.centre);
    const std::int64_t r = xy_interp::isqrt64(static_cast<std::uint64_t>(std::int64_t{rs[0]} * rs[0] + std::int64_t{rs[1]} * rs[1]));
    const std::uint64_t cap = xy_interp::isqrt64(static_cast<std::uint64_t>(lim.motion.a_max) * static_cast<std::uint64_t>(r) / 2U);
    if (cap < static_cast<std::uint64_t>(q.motion.v_max)) q.motion.v_max = cap > 0 ? static_cast<std::int32_t>(cap) : 1;
  }
  bool tangent = false;
  if (count_ > 0) {
    Queued& prev = at(count_ - 1);
    const xy_lookahead::Junction j = xy_lookahead::junction(exit_direction(prev.seg), entry_direction(s));
    // A chain longer than the profile's range is split at this junction (a stop there).
    tangent = !closed_ && j.kind == xy_lookahead::JunctionKind::Straight && open_bound_ + bound <= xy_scurve::kMaxMoves;
    prev.tangent_next = tangent;
  }
  open_bound_ = tangent ? open_bound_ + bound : bound;
  at(count_) = q;
  ++count_;
  closed_ = false;
  return Error::None;
}

}  // namespace ap::xy_path
