// The queue's chains on the move (docs/cnc.md "On the board"): the chain at the head found,
// closed (docs/cnc.md "Chains": a non-tangent segment, path_end or a full queue) and its arcs
// counted within the tick's budget, one S-curve planned over its moves at its segments' lowest
// limits (docs/cnc.md "Speeds"), then walked move by move each tick: one DIR per axis and tick,
// the axes' speeds from the tangent (docs/cnc.md "Axis speeds and reversal inside a tick"), the
// halt at an endstop and the controlled stop (docs/cnc.md "Stops"). What the queue takes is
// segments.cpp's.
#include "core/xy/path/executor.hpp"

#include "points.hpp"

namespace ap::xy_path {

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
