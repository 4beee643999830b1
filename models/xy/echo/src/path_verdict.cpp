// Whether a path frame is refused (docs/cnc.md "Refusals", "Speeds"; the decisions where it is
// silent in docs/echo-model.md "The coordinated path": a centre is only stored, an arc's end
// on an axis direction counts as passing it, a segment beside a motion command of its frame or
// cycle is refused). One pure function, reading the model and changing nothing, with the
// limits and the geometry it needs: mixed parts, homed and busy axes, a running stop, the
// ends and an arc's swept extremes against the soft limits, lengths and move bounds, the
// S-curve's limits, the queue. path.cpp acts on the verdict.
#include "models/xy/echo/echo_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace ap::model::xy_echo {
namespace {

using xy_codec::CommandId;

// docs/cnc.md "Refusals": a segment's |delta| <= 2^24 usteps, an arc's offsets <= 2^20 usteps;
// the queue holds 16 segments.
constexpr std::int64_t kPathMaxDelta = std::int64_t{1} << 24;
constexpr std::int64_t kPathMaxOffset = std::int64_t{1} << 20;
constexpr std::uint32_t kPathQueue = 16;
// docs/cnc.md "Refusals": one segment of more than 2^20 moves (the S-curve's range) is TooLong;
// a line makes max |delta| moves (one driving step per move, "Speeds"), an arc is judged by the
// bound docs/cnc.md states, not by counting it. A longer *chain* is split, never refused.
constexpr std::int64_t kPathMaxMoves = std::int64_t{1} << 20;
// docs/cnc.md "Speeds": the jerk is the thesis's J = 20 mm/s^3 (seed-003.md §5.3.1), converted
// with the mechanics; v_max, a_max and J must lie in xy_scurve::Limits' ranges (BadLimits):
// v 1 .. 100 000 moves/s, a >= 1, J 1 .. 1e9, J <= 1000 a, J <= 1e6 v.
constexpr std::int64_t kPathJerkUm = 20000;
constexpr std::int64_t kPathMaxVelocity = 100000;
constexpr std::int64_t kPathMaxJerk = 1000000000;

std::int64_t isqrt_floor(std::int64_t v) {  // v >= 0
  auto r = static_cast<std::int64_t>(std::sqrt(static_cast<double>(v)));
  while (r * r > v) --r;
  while ((r + 1) * (r + 1) <= v) ++r;
  return r;
}

// Whether an arc around the origin from angle a0 to a1 (radians, atan2) passes angle t
// (inclusive at both ends: an end lying exactly on an axis direction counts as passing it,
// docs/echo-model.md "The coordinated path"). ccw: counter-clockwise (y up); a full circle
// (a0 == a1, start == end) passes everything.
bool arc_passes(double a0, double a1, double t, bool ccw, bool full) {
  if (full) return true;
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  constexpr double kEps = 1e-12;
  const auto norm = [&](double v) {
    v = std::fmod(v, kTwoPi);
    return v < 0 ? v + kTwoPi : v;
  };
  double sweep = ccw ? norm(a1 - a0) : norm(a0 - a1);
  if (sweep <= kEps) sweep = kTwoPi;
  const double d = ccw ? norm(t - a0) : norm(a0 - t);
  return d <= sweep + kEps || d >= kTwoPi - kEps;
}

}  // namespace

const char* EchoModel::path_verdict(const xy_frame::CommandFrame& f, std::array<std::int32_t, kAxes>& end) const {
  const std::array<const xy_frame::AxisCommand*, kAxes> part{&f.x, &f.y};
  bool line = false, cw = false, ccw = false, centre = false;
  for (const auto* q : part) {
    line |= q->id == CommandId::PathLine;
    cw |= q->id == CommandId::PathArcCw;
    ccw |= q->id == CommandId::PathArcCcw;
    centre |= q->id == CommandId::PathCentre;
  }
  const int kinds = int{line} + int{cw} + int{ccw};
  if (kinds > 1 || (centre && kinds > 0)) return "mixed parts";  // MixedParts
  // cnc.md "Refusals": a centre frame without both parts is MixedParts too.
  if (centre && (f.x.id != CommandId::PathCentre || f.y.id != CommandId::PathCentre)) return "centre without both parts";
  if (centre) return nullptr;  // a centre is only stored (decision, docs/echo-model.md)
  // cnc.md "Refusals": a segment beside a motion command or a stop is MixedParts.
  for (const auto* q : part) {
    if (q->id == CommandId::Stop || q->id == CommandId::Jog || q->id == CommandId::Goto || q->id == CommandId::Move ||
        q->id == CommandId::GotoSlow || q->id == CommandId::MoveSlow || q->id == CommandId::Home) {
      return "a segment beside a motion command";
    }
  }
  // A motion command accepted earlier in this cycle is only stored: the segment supersedes it
  // (docs/board.md "One cycle"; supersede()), so the axes count as the axis core knows them.
  const auto known = [&](std::size_t a) -> const Ax& { return ax_[a].started_now ? at_tick_start_[a] : ax_[a]; };
  if (!known(0).homed || !known(1).homed) return "not homed";
  if (sleeping_) return "sleeping";
  for (std::size_t a = 0; a < kAxes; ++a) {
    // Busy: moving on its own, or a motion command accepted earlier in this tick (docs/cnc.md).
    if (ax_[a].started_now || known(a).act != Activity::Idle) return "an axis moves on its own";
  }
  if (path_.running && path_.stop != PathStop::None) return "a stop is running";  // Stopping
  if ((cw || ccw) && !path_.centre_set) return "arc without a centre";             // NoCentre
  // The segment starts where the queue ends, or at the axes' position when nothing is queued.
  const std::array<std::int64_t, kAxes> start{path_.running ? path_.end[0] : ax_[0].last.pos,
                                              path_.running ? path_.end[1] : ax_[1].last.pos};
  std::array<std::int64_t, kAxes> e{};
  for (std::size_t a = 0; a < kAxes; ++a) {
    // cnc.md step 3: um -> usteps nearest, as goto; a part carrying something else keeps the
    // axis where the queue ends.
    e[a] = (part[a]->id == CommandId::PathLine || part[a]->id == CommandId::PathArcCw ||
            part[a]->id == CommandId::PathArcCcw)
               ? to_usteps(part[a]->data)
               : start[a];
    if (e[a] < limit_min(a) || e[a] > limit_max(a)) return "end outside the soft limits";
    if (std::llabs(e[a] - start[a]) > kPathMaxDelta) return "too long";
  }
  if (line) {
    if (e == start) return "zero length";
    if (std::max(std::llabs(e[0] - start[0]), std::llabs(e[1] - start[1])) > kPathMaxMoves) return "too long";
  } else {
    std::array<std::int64_t, kAxes> c{};
    for (std::size_t a = 0; a < kAxes; ++a) {
      // cnc.md step 2: the centre's absolute position in um, converted like an end.
      c[a] = to_usteps(path_.centre_um[a]);
      if (std::llabs(c[a] - start[a]) > kPathMaxOffset) return "too long";
    }
    if (c == start || c == e) return "zero radius";
    const auto sq = [](std::int64_t v) { return v * v; };
    const std::int64_t rs = isqrt_floor(sq(start[0] - c[0]) + sq(start[1] - c[1]));
    const std::int64_t re = isqrt_floor(sq(e[0] - c[0]) + sq(e[1] - c[1]));
    // max(2 steps, 0.1 % of r): for integers |rs - re| > r/1000 exactly when > floor(r/1000).
    const std::int64_t tol = rs / 1000 > 2 ? rs / 1000 : 2;
    if (std::llabs(rs - re) > tol) return "radius mismatch";
    // docs/cnc.md "Refusals": an arc's moves are bounded by (r + 2) * 5794 / 1024 + 2 |rs - re| + 32.
    if ((rs + 2) * 5794 / 1024 + 2 * std::llabs(rs - re) + 32 > kPathMaxMoves) return "too long";
    // Swept extremes along each axis direction the arc passes (in double): c +- k with k the
    // largest integer with k - 1/2 < r, r the exact start radius in steps (cnc.md "Refusals":
    // every raster point is within 1/2 step of the circle).
    const double a0 = std::atan2(static_cast<double>(start[1] - c[1]), static_cast<double>(start[0] - c[0]));
    const double a1 = std::atan2(static_cast<double>(e[1] - c[1]), static_cast<double>(e[0] - c[0]));
    const bool full = e == start;
    const double r_exact = std::sqrt(static_cast<double>(sq(start[0] - c[0]) + sq(start[1] - c[1])));
    const double reach = std::ceil(r_exact + 0.5) - 1.0;
    constexpr double kHalfPi = 1.57079632679489661923;
    for (int k = 0; k < 4; ++k) {
      if (!arc_passes(a0, a1, k * kHalfPi, ccw, full)) continue;
      const std::size_t a = (k % 2 == 0) ? 0 : 1;  // 0, 180 deg: x; 90, 270 deg: y
      const double extreme = static_cast<double>(c[a]) + (k < 2 ? reach : -reach);
      if (extreme > static_cast<double>(limit_max(a)) || extreme < static_cast<double>(limit_min(a))) {
        return "swept extreme outside the soft limits";
      }
    }
  }
  {
    // cnc.md "Speeds": the path's v_max is the axes' fast speed, at most 100 000 moves/s.
    const std::int64_t v = std::min<std::int64_t>(to_usteps(p_.fast), kPathMaxVelocity);
    const std::int64_t acc = to_usteps(p_.accel), j = to_usteps(kPathJerkUm);
    if (v < 1 || v > kPathMaxVelocity || acc < 1 || j < 1 || j > kPathMaxJerk || j > 1000 * acc || j > 1000000 * v) {
      return "speed, acceleration or jerk outside scurve's ranges";  // BadLimits
    }
  }
  if (path_.queued + path_.added >= kPathQueue) return "queue full";
  for (std::size_t a = 0; a < kAxes; ++a) end[a] = static_cast<std::int32_t>(e[a]);
  return nullptr;
}

}  // namespace ap::model::xy_echo
