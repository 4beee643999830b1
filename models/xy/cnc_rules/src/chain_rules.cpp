// The chain-rule checker (chain_rules.hpp, ChainChecker): docs/cnc.md's rules ("Chains",
// "Speeds", "Refusals", "Safety properties") applied to what a PC and a logic analyser see,
// each cited where it is checked. One class: tick() checks every rule on the same tick's
// observations in one pass, because the rules share what it derives from them (the move rate,
// the segments the tick ran on, the rest that frees a chain) and the order matters (path.on
// finds the segment the caps are read from). The quantities the rules are stated in (caps,
// tangency, move and time bounds, the raster) are quantities.cpp's. Nothing here reads
// core/path.
#include "models/xy/cnc_rules/chain_rules.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>

namespace ap::model::xy_cnc_rules {

namespace {

constexpr double kTick = 0.001;  // the control tick, s (docs/scurve.md: whole 1 ms ticks)
// Reported speeds are thousandths truncated toward zero (docs/scurve.md "kinematics"); the
// caps are real numbers: a few thousandths of a move/s of slack, never a fraction of a cap.
constexpr double kEps = 0.005;

std::string str(const Point& p) {
  std::ostringstream o;
  o << "(" << p[0] << "," << p[1] << ")";
  return o.str();
}

}  // namespace

// ---- the checker -----------------------------------------------------------------------------

ChainChecker::ChainChecker(const Config& c, const Point& at) : c_(c), pos_(at) {}

void ChainChecker::fail(const std::string& rule, const std::string& what) {
  if (violations_.size() < 1000) violations_.push_back({tick_, rule, what});
}

std::string ChainChecker::report() const {
  std::ostringstream o;
  for (std::size_t k = 0; k < violations_.size() && k < 8; ++k) {
    o << "tick " << violations_[k].tick << " [" << violations_[k].rule << "] " << violations_[k].what << "\n";
  }
  if (violations_.size() > 8) o << "... " << violations_.size() - 8 << " more\n";
  return o.str();
}

std::size_t ChainChecker::head_chain_end() const {
  std::size_t e = freed_;
  while (e + 1 < segs_.size() && chain_next_[e]) ++e;
  return e;
}

bool ChainChecker::head_closed(std::string* why) const {
  if (freed_ >= segs_.size()) return false;
  const std::size_t e = head_chain_end();
  // docs/cnc.md "Chains": closed once a non-tangent segment follows, path_end came after its
  // last segment, or the queue is full.
  if (e + 1 < segs_.size()) {
    if (why) *why = "a segment that does not continue it follows";
    return true;
  }
  if (end_after_[e]) {
    if (why) *why = "path_end came after its last segment";
    return true;
  }
  if (segs_.size() - freed_ >= c_.queue) {
    if (why) *why = "the queue is full";
    return true;
  }
  if (cut_next_[e]) {
    if (why) *why = "it reached 2^20 moves";
    return true;
  }
  return false;
}

std::uint64_t ChainChecker::start_bound(std::size_t from, std::size_t to) const {
  // docs/cnc.md "Chains": the arcs' moves are counted at most 4096 a tick before the chain
  // starts; the count is at most the docs' move bound of each arc ("Refusals", TooLong).
  double arc_moves = 0;
  for (std::size_t k = from; k <= to && k < segs_.size(); ++k) {
    if (segs_[k].kind != Kind::Line) arc_moves += static_cast<double>(moves_bound(segs_[k]));
  }
  return static_cast<std::uint64_t>(std::ceil(arc_moves / c_.count_budget)) + 2 + creep_ticks(c_);
}

std::uint64_t ChainChecker::remaining_ticks_bound() const {
  std::uint64_t total = 0;
  std::size_t k = freed_;
  while (k < segs_.size()) {
    const std::size_t from = k;
    double moves = 0;
    double cap = std::numeric_limits<double>::infinity();
    for (;; ++k) {
      moves += static_cast<double>(moves_bound(segs_[k]));
      cap = std::min(cap, caps_[k]);
      if (k + 1 >= segs_.size() || !chain_next_[k]) break;
    }
    total += start_bound(from, k) + chain_ticks_bound(c_, moves, cap);
    ++k;
  }
  return total;
}

void ChainChecker::accepted(const Segment& s) {
  const std::size_t k = segs_.size();
  // docs/cnc.md "Refusals": QueueFull when 16 segments wait. The checker counts a segment as
  // waiting until its chain has run to rest; a board that frees earlier may accept more.
  if (waiting_) {
    longest_wait_ = std::max(longest_wait_, tick_ - wait_since_);
    waiting_ = false;
    wait_reported_ = false;
  }
  const std::uint64_t mb = moves_bound(s);
  if (k > 0) {
    const bool tan = tangent(segs_[k - 1], s);
    bool chain = tan && !end_after_[k - 1] && !cut_next_[k - 1];
    // docs/cnc.md "Refusals": a chain longer than 2^20 moves is split at the junction that
    // would exceed the range.
    if (chain && open_moves_ + mb > c_.max_chain_moves) {
      chain = false;
      cut_next_[k - 1] = true;
    }
    chain_next_[k - 1] = chain;
    open_moves_ = chain ? open_moves_ + mb : mb;
  } else {
    open_moves_ = mb;
  }
  segs_.push_back(s);
  caps_.push_back(segment_cap(c_, s));
  chain_next_.push_back(false);
  cut_next_.push_back(false);
  end_after_.push_back(false);
  // The queue is full now and the head chain still open: it starts without its end, so the
  // chain ends (at rest) after this segment, whatever comes next.
  if (segs_.size() - freed_ >= c_.queue && head_chain_end() == k && !end_after_[k]) cut_next_[k] = true;
}

void ChainChecker::refused_queue_full() {
  const std::size_t waiting = segs_.size() - freed_;
  if (waiting < c_.queue) {
    fail("queue.full",
         "QueueFull with " + std::to_string(waiting) + " segments waiting (docs/cnc.md \"Refusals\": 16)");
  }
  if (waiting_) return;
  waiting_ = true;
  wait_since_ = tick_;
  wait_reported_ = false;
  // docs/cnc.md "Chains": the head chain is closed (the queue is full); it starts within the
  // count bound and frees its segments when its S-curve has run.
  wait_bound_ = 0;
  if (freed_ < segs_.size()) {
    const std::size_t e = head_chain_end();
    double moves = 0;
    double cap = std::numeric_limits<double>::infinity();
    for (std::size_t k = freed_; k <= e; ++k) {
      moves += static_cast<double>(moves_bound(segs_[k]));
      cap = std::min(cap, caps_[k]);
    }
    wait_bound_ = start_bound(freed_, e) + chain_ticks_bound(c_, moves, cap);
  }
}

void ChainChecker::path_end() {
  if (!segs_.empty()) end_after_.back() = true;
  if (!end_sent_) {
    end_tick_ = tick_;
    end_deadline_ = tick_ + remaining_ticks_bound();
  }
  end_sent_ = true;
}

void ChainChecker::tick(const Point& pos, const std::array<std::int64_t, 2>& v_fine,
                        const std::array<std::int32_t, 2>& steps) {
  ++tick_;
  // docs/cnc.md "Axis speeds": an axis's speed is the move rate times its share of the
  // tangent, 1 for the driving axis: the path's move rate is the larger axis speed.
  const double v = static_cast<double>(std::max(std::llabs(v_fine[0]), std::llabs(v_fine[1]))) / 1000.0;
  const bool stepped = steps[0] != 0 || steps[1] != 0;
  const bool moved = pos != pos_;
  const double cheb = static_cast<double>(std::max(std::llabs(pos[0] - pos_[0]), std::llabs(pos[1] - pos_[1])));
  const std::size_t prev_cur = cur_;
  const bool have = !segs_.empty();
  // Standing at the end of the segment it has run: the motion goes on with the next segment
  // (a full circle's end is its start too).
  const bool prev_at_end = have && entered_ && pos_ == segs_[cur_].end;

  // path.on: the earliest segment from the current one that holds the new position (from the
  // next one when the current one is done).
  if (moved) {
    bool found = false;
    for (std::size_t from : {prev_at_end ? cur_ + 1 : cur_, cur_}) {
      for (std::size_t j = from; j < segs_.size() && !found; ++j) {
        if (on_segment(segs_[j], pos)) {
          cur_ = j;
          found = true;
        }
      }
      if (found) break;
    }
    if (found) entered_ = true;
    if (!found) fail("path.on", "position " + str(pos) + " on no submitted segment from #" + std::to_string(cur_));
  }

  // The segments the tick ran on: from where it started (the next one if it started at the
  // end of its segment) to where it ended.
  std::size_t lo = prev_cur;
  std::size_t hi = cur_;
  if (moved && prev_at_end && hi > lo) ++lo;
  if (!moved && rest_at_end_ && cur_ + 1 < segs_.size()) lo = hi = cur_ + 1;  // creeping off a rest
  double allowance = std::min(c_.v_max, 100000.0);
  if (have) {
    allowance = std::numeric_limits<double>::infinity();
    for (std::size_t k = lo; k <= hi; ++k) allowance = std::min(allowance, caps_[k]);
  }

  if (have) {
    const double slack_a = c_.a_max * kTick;  // one tick of acceleration
    // cap.segment: the speed where the tick ends, within that segment's cap.
    const std::size_t here = (!moved && rest_at_end_ && cur_ + 1 < segs_.size()) ? cur_ + 1 : cur_;
    if (v > caps_[here] + kEps) {
      std::ostringstream o;
      o << "speed " << v << " moves/s on segment #" << here << " (" << (segs_[here].kind == Kind::Line ? "line" : "arc")
        << ") above its cap " << caps_[here];
      fail("cap.segment", o.str());
    }
    // cap.join: a join crossed in the tick (inside it, or leaving a join it started on).
    const bool crossed = moved && (hi > lo || (prev_at_end && hi > prev_cur));
    if (crossed) {
      for (const double vv : {v_prev_, v}) {
        if (vv > allowance + slack_a + kEps) {
          std::ostringstream o;
          o << "speed " << vv << " moves/s across the join(s) from #" << prev_cur << " to #" << hi
            << " above the lowest cap " << allowance;
          fail("cap.join", o.str());
          break;
        }
      }
    }
    // cap.centripetal on an arc (not across a join).
    if (moved && lo == hi && segs_[hi].kind != Kind::Line) {
      const double r = arc_radius(segs_[hi]);
      const double ve = std::hypot(static_cast<double>(v_fine[0]), static_cast<double>(v_fine[1])) / 1000.0;
      const double ratio = ve * ve / (r * c_.a_max);
      max_centripetal_ = std::max(max_centripetal_, ratio);
      max_arc_ratio_ = std::max(max_arc_ratio_, v / caps_[hi]);
      if (ratio > 1.0 * (1 + 1e-6) + kEps) {
        std::ostringstream o;
        o << "centripetal acceleration " << ve * ve / r << " on arc #" << hi << " (r " << r << ") above a_max";
        fail("cap.centripetal", o.str());
      }
    }
    // corner.rest: a junction that is not tangent, or that path_end closed, is passed from rest.
    if (moved && hi > prev_cur) {
      for (std::size_t m = prev_cur; m < hi; ++m) {
        if (chain_next_[m] || cut_next_[m]) continue;
        const bool from_rest_here = rest_at_end_ && pos_ == segs_[m].end;
        if (!from_rest_here) {
          fail("corner.rest", "junction #" + std::to_string(m) + "/#" + std::to_string(m + 1) + " at " +
                                  str(segs_[m].end) + " passed without a rest (not tangent or closed by path_end)");
        }
      }
    }
  } else if (moved || v > 0) {
    fail("path.on", "motion with no segment submitted");
  }

  // Motion episodes: rest to rest (docs/cnc.md "Chains": one S-curve per chain, rest to rest).
  const bool motion = moved || v > 0 || stepped;
  if (!moving_ && motion) {
    moving_ = true;
    if (first_motion_ == ~std::uint64_t{0}) first_motion_ = tick_;
    std::string why;
    // start.open: "A chain starts once it is closed".
    if (!head_closed(&why)) {
      fail("start.open", "motion started while the chain at #" + std::to_string(freed_) + " is still open");
    }
    episode_max_v_ = 0;
    episode_min_cap_ = std::numeric_limits<double>::infinity();
  }
  if (moving_) {
    episode_min_cap_ = std::min(episode_min_cap_, allowance);
    if (v > episode_max_v_) {
      episode_max_v_ = v;
      episode_max_tick_ = tick_;
    }
  }
  if (moved) rest_at_end_ = false;

  // A rest after motion: the chain has run. Its speed is 0 and its last move is made in this
  // tick (the profile reaches the chain's last move exactly at its end, docs/scurve.md
  // "exact arrival"); the ticks just before it creep below 1/1000 move/s without a move.
  const bool rested = moving_ && v == 0 && (stepped || (freed_ < segs_.size() && pos == segs_[head_chain_end()].end));
  if (rested) {
    ++rests_;
    moving_ = false;
    // cap.chain: the chain's v_max is its segments' lowest cap ("Speeds").
    if (episode_max_v_ > episode_min_cap_ + kEps) {
      std::ostringstream o;
      o << "speed " << episode_max_v_ << " moves/s (tick " << episode_max_tick_
        << ") in a chain whose lowest segment cap is " << episode_min_cap_;
      fail("cap.chain", o.str());
    }
    if (freed_ < segs_.size()) {
      const std::size_t e = head_chain_end();
      if (pos == segs_[e].end) {
        freed_ = e + 1;
        cur_ = e;
        entered_ = true;
        rest_at_end_ = true;
      } else {
        bool at_junction = false;
        for (std::size_t k = std::max(cur_, freed_); k < e; ++k) {
          if (pos == segs_[k].end) {
            // tangent.kept: the chain continues here and was not cut: no rest.
            fail("tangent.kept", "rest at the tangent junction #" + std::to_string(k) + "/#" + std::to_string(k + 1) +
                                     " at " + str(pos) + " inside the chain #" + std::to_string(freed_) + "..#" +
                                     std::to_string(e));
            freed_ = k + 1;
            cur_ = k;
            entered_ = true;
            rest_at_end_ = true;
            at_junction = true;
            break;
          }
        }
        if (!at_junction) fail("rest.inside", "rest at " + str(pos) + " inside segment #" + std::to_string(cur_));
      }
    } else {
      fail("rest.inside", "rest at " + str(pos) + " with no segment left");
    }
  }

  // live.start: a closed chain standing still too long.
  const bool progress = moved || v > 0 || rested;
  std::string why;
  if (progress) {
    idle_ = 0;
    live_reported_ = false;
  } else if (head_closed(&why)) {
    ++idle_;
    const std::uint64_t bound = start_bound(freed_, head_chain_end());
    if (idle_ > bound && !live_reported_) {
      live_reported_ = true;
      fail("live.start", "the chain at #" + std::to_string(freed_) + " is closed (" + why + ") and stood " +
                             std::to_string(idle_) + " ticks (bound " + std::to_string(bound) + ")");
    }
  } else {
    idle_ = 0;
  }
  // live.space: the PC waiting for queue space.
  if (waiting_) {
    longest_wait_ = std::max(longest_wait_, tick_ - wait_since_);
    if (tick_ - wait_since_ > wait_bound_ && !wait_reported_) {
      wait_reported_ = true;
      fail("live.space", "the PC has waited " + std::to_string(tick_ - wait_since_) + " ticks for queue space (bound " +
                             std::to_string(wait_bound_) + ")");
    }
  }

  // live.end: the path at rest at its end by the deadline path_end set.
  if (end_sent_ && !end_reported_ && tick_ > end_deadline_ && (moving_ || freed_ < segs_.size())) {
    end_reported_ = true;
    fail("live.end", "the path has not ended " + std::to_string(tick_ - end_tick_) +
                         " ticks after path_end (bound " + std::to_string(end_deadline_ - end_tick_) + ", " +
                         std::to_string(segs_.size() - freed_) + " segments not run)");
  }

  ticks_.push_back({v, allowance, cheb});
  check_window();
  pos_ = pos;
  v_prev_ = v;
}

void ChainChecker::check_window() {
  // cap.steps: moves in ticks t0..t1 >= the Chebyshev distances; they fit the integral of the
  // caps over ticks t0-1..t1 (one tick of reversal lag) plus 2 (whole moves).
  const std::size_t n = ticks_.size();
  const std::size_t w = c_.window;
  if (n < w + 1) return;
  double moves = 0;
  double allowed = 0;
  for (std::size_t t = n - w; t < n; ++t) moves += ticks_[t].cheb;
  for (std::size_t t = n - w - 1; t < n; ++t) allowed += ticks_[t].allowance * kTick;
  if (moves > allowed + 2 + 1e-9) {
    std::ostringstream o;
    o << moves << " moves in " << w << " ticks, the caps allow " << allowed << " + 2";
    fail("cap.steps", o.str());
  }
}

void ChainChecker::finish() {
  if (waiting_) fail("live.space", "the run ended with the PC still waiting for queue space");
  if (moving_) fail("rest.inside", "the run ended with the path moving");
  if (!segs_.empty() && end_sent_ && pos_ != segs_.back().end) {
    // docs/cnc.md "Safety properties": a path that ends without a stop ends exactly at the end
    // of its last segment.
    fail("path.end", "the path ended at " + str(pos_) + ", its last segment at " + str(segs_.back().end));
  }
  if (freed_ < segs_.size() && end_sent_) {
    fail("path.end", std::to_string(segs_.size() - freed_) + " segments never ran");
  }
}

}  // namespace ap::model::xy_cnc_rules
