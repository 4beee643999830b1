// The docs' quantities the chain rules are stated in (chain_rules.hpp, "the docs' quantities"):
// a segment's speed cap (docs/cnc.md "Speeds"), its direction where it starts and where it ends
// and whether a junction is tangent (docs/cnc.md "Chains"), its move bound (docs/cnc.md
// "Refusals", TooLong), the time bounds of a chain's S-curve (seed-003.md §5.4, docs/scurve.md
// "Planning") and whether a position lies on a segment's raster (docs/interpolation.md;
// seed-003.md §3.2, §3.3). Pure functions of a segment and the config, apart from the checker
// (chain_rules.cpp) that applies them tick by tick. Nothing here reads core/path.
#include "models/xy/cnc_rules/chain_rules.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

namespace ap::model::xy_cnc_rules {

namespace {

std::int64_t cross(const Point& a, const Point& b) { return a[0] * b[1] - a[1] * b[0]; }
std::int64_t dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1]; }
Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1]}; }

std::uint64_t isqrt(std::uint64_t v) {
  auto r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(v)));
  while (r * r > v) --r;
  while ((r + 1) * (r + 1) <= v) ++r;
  return r;
}

// The counter-clockwise angle from a to b in [0, 2 pi).
double ccw_angle(const Point& a, const Point& b) {
  double t = std::atan2(static_cast<double>(cross(a, b)), static_cast<double>(dot(a, b)));
  if (t < 0) t += 2 * std::numbers::pi;
  return t;
}

}  // namespace

double arc_radius(const Segment& s) {
  const Point r = sub(s.start, s.centre);
  return std::hypot(static_cast<double>(r[0]), static_cast<double>(r[1]));
}

double segment_cap(const Config& c, const Segment& s) {
  // docs/cnc.md "Speeds": the path runs at the axes' `fast`, capped at 100 000 moves/s; F does
  // not set the speed (the thesis ignores F, seed-003.md §2.5). On an arc of radius r steps
  // the chain's move rate is further capped at sqrt(a_max r / 2) [D]: a move is up to sqrt(2)
  // steps long, so the real centripetal acceleration stays within a_max.
  double cap = std::min(c.v_max, 100000.0);
  if (s.kind != Kind::Line) cap = std::min(cap, std::sqrt(c.a_max * arc_radius(s) / 2.0));
  return cap;
}

Point entry_direction(const Segment& s) {
  if (s.kind == Kind::Line) return sub(s.end, s.start);
  const Point r = sub(s.start, s.centre);
  // Moving counter-clockwise (y up) at radius r the motion is r turned by +90 deg.
  return s.kind == Kind::ArcCcw ? Point{-r[1], r[0]} : Point{r[1], -r[0]};
}

Point exit_direction(const Segment& s) {
  if (s.kind == Kind::Line) return sub(s.end, s.start);
  const Point r = sub(s.end, s.centre);
  return s.kind == Kind::ArcCcw ? Point{-r[1], r[0]} : Point{r[1], -r[0]};
}

bool tangent(const Segment& in, const Segment& out) {
  const Point a = exit_direction(in);
  const Point b = entry_direction(out);
  return cross(a, b) == 0 && dot(a, b) > 0;
}

std::uint64_t moves_bound(const Segment& s) {
  if (s.kind == Kind::Line) {
    const Point d = sub(s.end, s.start);
    return static_cast<std::uint64_t>(std::max(std::llabs(d[0]), std::llabs(d[1])));
  }
  const Point rs = sub(s.start, s.centre);
  const Point re = sub(s.end, s.centre);
  const std::uint64_t r = isqrt(static_cast<std::uint64_t>(dot(rs, rs)));
  const std::uint64_t r_e = isqrt(static_cast<std::uint64_t>(dot(re, re)));
  const std::uint64_t dr = r > r_e ? r - r_e : r_e - r;
  return (r + 2) * 5794 / 1024 + 2 * dr + 32;
}

std::uint64_t chain_ticks_bound(const Config& c, double moves, double v) {
  v = std::max(1.0, std::min(v, 100000.0));
  const double a = c.a_max;
  const double j = c.j_max;
  // Continuous rest-to-rest minimum time (seed-003.md §5.4): with v reached, the ramp takes
  // v/a' + a'/j each way, a' = min(a, sqrt(v j)); a shorter path takes no longer than the
  // distance that just reaches v (the time grows with the distance).
  const double ap = std::min(a, std::sqrt(v * j));
  const double l_v = v * (v / ap + ap / j);
  const double t = std::max(moves, l_v) / v + v / ap + ap / j;
  // docs/scurve.md "Planning": whole ticks cost up to ~2T/Tj more, Tj the jerk phase in ticks.
  const double tj = std::max(1.0, std::min(std::floor(1000 * a / j), std::floor(std::sqrt(1e6 * v / j))));
  return static_cast<std::uint64_t>(std::ceil(1000 * t * (2 + 4 / tj))) + 50;
}

std::uint64_t creep_ticks(const Config& c) {
  // v = (J/8) t^2 / 2 >= 1/1000 move/s from rest.
  return static_cast<std::uint64_t>(std::ceil(1000 * std::sqrt(0.016 / c.j_max))) + 2;
}

bool on_segment(const Segment& s, const Point& p) {
  if (s.kind == Kind::Line) {
    // Bresenham (seed-003.md §3.2, docs/interpolation.md): the major axis runs from start to
    // end, the minor axis within 1/2 step of the ideal line.
    const Point d = sub(s.end, s.start);
    const std::size_t M = std::llabs(d[0]) >= std::llabs(d[1]) ? 0 : 1;
    const std::size_t m = 1 - M;
    if (p[M] < std::min(s.start[M], s.end[M]) || p[M] > std::max(s.start[M], s.end[M])) return false;
    const double ideal = static_cast<double>(s.start[m]) +
                         static_cast<double>(p[M] - s.start[M]) * static_cast<double>(d[m]) / static_cast<double>(d[M]);
    return std::abs(static_cast<double>(p[m]) - ideal) <= 0.5 + 1e-9;
  }
  // Midpoint circle (seed-003.md §3.3): within 1/2 step of the circle through the start, or on
  // the tail to an end off it (between the two radii); and inside the swept angle.
  const Point rs = sub(s.start, s.centre);
  const Point re = sub(s.end, s.centre);
  const Point rp = sub(p, s.centre);
  const double r_s = std::hypot(static_cast<double>(rs[0]), static_cast<double>(rs[1]));
  const double r_e = std::hypot(static_cast<double>(re[0]), static_cast<double>(re[1]));
  const double rho = std::hypot(static_cast<double>(rp[0]), static_cast<double>(rp[1]));
  if (rho > std::max(r_s, r_e) + 0.5 + 1e-9 || rho < std::min(r_s, r_e) - 1.5 - 1e-9) return false;
  if (rho == 0) return false;
  const bool ccw = s.kind == Kind::ArcCcw;
  double sweep = ccw ? ccw_angle(rs, re) : ccw_angle(re, rs);
  if (cross(rs, re) == 0 && dot(rs, re) > 0) sweep = 2 * std::numbers::pi;  // an end on the start's ray: a full circle
  const double at = ccw ? ccw_angle(rs, rp) : ccw_angle(rp, rs);
  // docs/interpolation.md "Stop rule": the circle phase stops at the first point whose angle
  // reaches or passes the end's, at most one move (a chord <= sqrt(2)) beyond it, then the tail
  // runs back to the end; no point lies before the start (half a step of rounding).
  return at <= sweep + 1.5 / rho || at >= 2 * std::numbers::pi - 0.5 / rho;
}

}  // namespace ap::model::xy_cnc_rules
