#include "core/xy/path/executor.hpp"

#include "core/xy/lookahead/junction.hpp"

namespace ap::xy_path {

namespace {

constexpr std::int64_t abs64(std::int64_t v) { return v < 0 ? -v : v; }

xy_lookahead::Turn la_turn(Kind k) { return k == Kind::ArcCw ? xy_lookahead::Turn::Cw : xy_lookahead::Turn::Ccw; }

std::array<std::int32_t, 2> rel(const Point& p, const Point& c) { return {p[0] - c[0], p[1] - c[1]}; }

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

void Executor::close() {
  if (count_ > 0) closed_ = true;
}

void Executor::stop() {
  if (status_ == Status::Running) {
    prof_ = xy_scurve::request_stop(plan_, prof_);
    status_ = Status::Stopping;
    // Only the running chain's segments stay, to walk to where the stop ends.
    count_ = chain_n_;
    closed_ = true;
    return;
  }
  if (status_ != Status::Stopping) clear();
}

void Executor::clear() {
  count_ = 0;
  head_ = 0;
  closed_ = false;
  open_bound_ = 0;
  status_ = Status::Idle;
  counting_ = false;
  chain_n_ = 0;
  chain_moves_ = 0;
  done_ = 0;
  plan_ = xy_scurve::Plan{};
  prof_ = xy_scurve::start(plan_);
}

std::size_t Executor::chain_length() const {
  std::size_t n = 0;
  while (n < count_) {
    ++n;
    if (!at(n - 1).tangent_next) break;
  }
  return n;
}

bool Executor::chain_closed(std::size_t n) const { return n < count_ || closed_ || count_ == kQueue; }

bool Executor::count_arcs(std::size_t n) {
  std::uint32_t budget = kCountBudget;
  for (std::size_t k = 0; k < n; ++k) {
    Queued& q = at(k);
    if (q.counted) continue;
    if (!counting_ || counting_k_ != k) {
      const auto rs = rel(q.seg.start, q.seg.centre);
      const auto re = rel(q.seg.end, q.seg.centre);
      count_arc_ = xy_interp::Arc::make(rs, re, q.seg.kind == Kind::ArcCw ? xy_interp::Turn::Cw : xy_interp::Turn::Ccw).arc;
      count_n_ = 0;
      counting_ = true;
      counting_k_ = k;
    }
    while (!count_arc_.done() && budget > 0) {
      (void)count_arc_.next();
      ++count_n_;
      --budget;
    }
    if (!count_arc_.done()) return false;
    q.moves = count_n_;
    q.counted = true;
    counting_ = false;
  }
  return true;
}

void Executor::start_chain(std::size_t n) {
  chain_n_ = n;
  chain_seg_ = 0;
  done_ = 0;
  std::uint32_t total = 0;
  xy_scurve::Limits lim = at(0).motion;
  for (std::size_t k = 0; k < n; ++k) {
    const Queued& q = at(k);
    total += q.moves;
    // One profile for the chain: the lowest of its segments' limits.
    if (q.motion.v_max < lim.v_max) lim.v_max = q.motion.v_max;
    if (q.motion.a_max < lim.a_max) lim.a_max = q.motion.a_max;
    if (q.motion.j_max < lim.j_max) lim.j_max = q.motion.j_max;
  }
  chain_moves_ = total;
  const xy_scurve::PlanResult pr = xy_scurve::plan(total, lim);
  if (pr.error != xy_scurve::Error::None) {  // add() checked each segment's limits; kept total
    clear();
    return;
  }
  plan_ = pr.plan;
  prof_ = xy_scurve::start(plan_);
  open_cursor();
  status_ = Status::Running;
}

void Executor::open_cursor() {
  const Segment& s = at(chain_seg_).seg;
  cur_.kind = s.kind;
  if (s.kind == Kind::Line) {
    cur_.line = xy_interp::Line({s.end[0] - s.start[0], s.end[1] - s.start[1], 0});
    cur_.origin = s.start;
    cur_.delta = {s.end[0] - s.start[0], s.end[1] - s.start[1]};
  } else {
    cur_.arc = xy_interp::Arc::make(rel(s.start, s.centre), rel(s.end, s.centre),
                                 s.kind == Kind::ArcCw ? xy_interp::Turn::Cw : xy_interp::Turn::Ccw)
                   .arc;
    cur_.origin = s.centre;
  }
}

void Executor::finish_chain() {
  head_ = (head_ + chain_n_) % kQueue;
  count_ -= chain_n_;
  if (count_ == 0) {
    head_ = 0;
    closed_ = false;
  }
  chain_n_ = 0;
  chain_moves_ = 0;
  done_ = 0;
  status_ = count_ > 0 ? Status::Waiting : Status::Idle;
}

bool Executor::Cursor::done() const { return kind == Kind::Line ? line.done() : arc.done(); }

std::array<std::int8_t, kAxes> Executor::Cursor::peek() const {
  Cursor c = *this;
  if (c.kind == Kind::Line) {
    const auto m = c.line.next();
    return {m[0], m[1]};
  }
  return c.arc.next();
}

void Executor::Cursor::advance() {
  if (kind == Kind::Line) {
    (void)line.next();
  } else {
    (void)arc.next();
  }
}

Point Executor::Cursor::tangent(const Point& pos) const {
  if (kind == Kind::Line) return delta;
  const std::int32_t x = pos[0] - origin[0];
  const std::int32_t y = pos[1] - origin[1];
  return kind == Kind::ArcCw ? Point{y, -x} : Point{-y, x};
}

xy_scurve::Kinematics Executor::kinematics() const {
  if (status_ != Status::Running && status_ != Status::Stopping) return {};
  return xy_scurve::kinematics(plan_, prof_);
}

TickOut Executor::tick(const TickIn& in, Point& pos, Halt& halt) {
  halt = Halt::None;
  TickOut out;
  out.dir = last_dir_;
  if (status_ == Status::Idle || status_ == Status::Waiting) {
    if (count_ == 0) {
      status_ = Status::Idle;
      return out;
    }
    const std::size_t n = chain_length();
    if (!chain_closed(n) || !count_arcs(n)) {
      status_ = Status::Waiting;
      return out;
    }
    start_chain(n);
    if (status_ != Status::Running) return out;
  }
  prof_ = xy_scurve::step(plan_, prof_);
  const std::uint32_t target = xy_scurve::moves_at(plan_, prof_);
  std::array<std::int8_t, kAxes> tick_dir{0, 0};
  while (done_ < target) {
    while (cur_.done() && chain_seg_ + 1 < chain_n_) {
      ++chain_seg_;
      open_cursor();
    }
    if (cur_.done()) break;  // cannot happen: the chain's moves are its segments' moves
    const auto m = cur_.peek();
    bool reverses = false;
    for (std::size_t a = 0; a < kAxes; ++a) {
      // All of a tick's steps share one DIR: a move against this tick's direction waits for
      // the next tick (docs/cnc.md "Reversal inside a tick").
      if (m[a] != 0 && tick_dir[a] != 0 && m[a] != tick_dir[a]) reverses = true;
    }
    if (reverses) break;
    for (std::size_t a = 0; a < kAxes; ++a) {
      if ((m[a] < 0 && in.toward_min_blocked[a]) || (m[a] > 0 && in.toward_max_blocked[a])) {
        halt = Halt::Endstop;
        for (std::size_t b = 0; b < kAxes; ++b) {
          if (tick_dir[b] != 0) last_dir_[b] = tick_dir[b];
        }
        out.dir = last_dir_;
        clear();
        return out;
      }
    }
    cur_.advance();
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (m[a] == 0) continue;
      pos[a] += m[a];
      ++out.steps[a];
      tick_dir[a] = m[a];
    }
    ++done_;
  }
  // Axis speeds: the move rate times each axis's share of the tangent (the driving axis, the
  // larger component, makes one step per move).
  const xy_scurve::Kinematics k = xy_scurve::kinematics(plan_, prof_);
  const Point t = cur_.tangent(pos);
  // DIR follows the motion: the direction of this tick's steps, else the sign of the axis's
  // tangent component, so DIR turns where the axis's speed passes zero (the top of an arc), not
  // at its first step, which comes when the axis already moves (docs/cnc.md "Axis speeds").
  for (std::size_t a = 0; a < kAxes; ++a) {
    if (tick_dir[a] != 0) {
      last_dir_[a] = tick_dir[a];
    } else if (t[a] != 0) {
      last_dir_[a] = t[a] > 0 ? std::int8_t{1} : std::int8_t{-1};
    }
  }
  out.dir = last_dir_;
  const std::int64_t tx = abs64(t[0]);
  const std::int64_t ty = abs64(t[1]);
  const std::int64_t major = tx > ty ? tx : ty;
  if (major > 0 && k.vel_milli > 0) {
    // vel_milli <= v_max * 1000 <= 1e8 and the share <= 1: each product < 2^63 for |t| < 2^24.
    out.v_fine[0] = static_cast<std::int32_t>(k.vel_milli * tx / major);
    out.v_fine[1] = static_cast<std::int32_t>(k.vel_milli * ty / major);
  }
  if (xy_scurve::finished(plan_, prof_) && done_ >= target) {
    out.finished_chain = true;
    out.v_fine = {0, 0};
    if (status_ == Status::Stopping) {
      clear();
    } else {
      finish_chain();
    }
  }
  return out;
}

}  // namespace ap::xy_path
