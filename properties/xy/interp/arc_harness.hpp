// Shared arc checks for arc_test.cpp and arc_circles_test.cpp (docs/interpolation.md "Arc").
// Every predicate is exact integer arithmetic or float geometry (models/xy/dda), stated here from
// the docs, never read from the code under test.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "core/xy/interp/arc.hpp"
#include "models/xy/dda/dda.hpp"

namespace ap::interp_test {

namespace xy_dda = ap::model::xy_dda;
using ap::xy_interp::Arc;
using ap::xy_interp::Error;
using ap::xy_interp::Turn;
using P = std::array<int32_t, 2>;

inline int64_t floor_sqrt(int64_t v) {  // independent of the core's isqrt64
  auto r = static_cast<int64_t>(std::sqrt(static_cast<double>(v)));
  while (r * r > v) --r;
  while ((r + 1) * (r + 1) <= v) ++r;
  return r;
}

// |sqrt(x^2+y^2) - sqrt(R2)| < 1/2, exactly: (4q - 4*R2 - 1)^2 < 16*R2 with q = x^2 + y^2.
inline bool radial_ok(P p, int64_t r2) {
  const int64_t q = int64_t{p[0]} * p[0] + int64_t{p[1]} * p[1];
  const int64_t t = 4 * q - 4 * r2 - 1;
  return t * t < 16 * r2;
}

inline int64_t cross(P a, P b) { return int64_t{a[0]} * b[1] - int64_t{a[1]} * b[0]; }

// The docs' termination bound: 8*floor(sqrt(R2)) + 8 circle moves, plus the tail's
// floor(sqrt(R2)) + 1 + max(|ex|, |ey|).
inline int64_t stated_bound(P s, P e) {
  const int64_t r = floor_sqrt(int64_t{s[0]} * s[0] + int64_t{s[1]} * s[1]);
  return 8 * r + 8 + r + 1 + std::max(std::abs(e[0]), std::abs(e[1]));
}

struct Trace {
  std::vector<P> points;  // including the start
  int64_t circle_moves = 0;
  std::string failure;
};

// Runs an arc and checks every move on the way (8-connected; in the circle phase: radial error
// < 1/2 and strictly turning the right way).
inline Trace trace(P s, P e, Turn turn) {
  Trace t;
  auto r = Arc::make(s, e, turn);
  if (r.error != Error::None) {
    t.failure = "refused";
    return t;
  }
  Arc& a = r.arc;
  const int64_t r2 = int64_t{s[0]} * s[0] + int64_t{s[1]} * s[1];
  const int64_t bound = stated_bound(s, e);
  if (a.max_moves() != bound) t.failure = "max_moves() is not the documented bound";
  t.points.push_back(a.position());
  bool circle = true;
  while (!a.done() && t.failure.empty()) {
    const bool was_tail = a.on_tail();
    if (was_tail) circle = false;
    const auto m = a.next();
    const P p = a.position();
    const P q = t.points.back();
    if (p[0] - q[0] != m[0] || p[1] - q[1] != m[1]) t.failure = "move does not match position";
    if (std::max(std::abs(m[0]), std::abs(m[1])) != 1) t.failure = "move is not 8-connected";
    if (circle) {
      ++t.circle_moves;
      if (!radial_ok(p, r2)) t.failure = "radial error >= 1/2";
      const int64_t c = cross(q, p);
      if (turn == Turn::Cw ? c >= 0 : c <= 0) t.failure = "did not turn the right way";
    }
    t.points.push_back(p);
    if (static_cast<int64_t>(t.points.size()) - 1 > bound) t.failure = "more moves than the bound";
  }
  if (t.failure.empty() && t.points.back() != e) t.failure = "did not end at the end point";
  if (t.failure.empty() && a.next() != std::array<int8_t, 2>{0, 0}) t.failure = "moved after done";
  return t;
}

inline double swept(P s, P p, Turn turn) {
  return xy_dda::swept_angle({s[0], s[1]}, {p[0], p[1]}, turn == Turn::Cw);
}

// A full circle (end == start): checks of trace(), plus: no tail, once around, back at the start.
inline std::string check_full_circle(P s, Turn turn) {
  const Trace t = trace(s, s, turn);
  if (!t.failure.empty()) return t.failure;
  if (t.circle_moves != static_cast<int64_t>(t.points.size()) - 1) return "a full circle used the tail";
  const int64_t r = floor_sqrt(int64_t{s[0]} * s[0] + int64_t{s[1]} * s[1]);
  if (t.circle_moves >= 8 * r + 8) return "the guard limit was reached";
  double total = 0;
  for (std::size_t i = 1; i < t.points.size(); ++i) total += swept(t.points[i - 1], t.points[i], turn);
  if (std::abs(total - 2 * std::numbers::pi) > 1e-6) return "not once around";
  return {};
}

}  // namespace ap::interp_test
