// Midpoint circle interpolation in the XY plane, integers only (seed-003.md §3.3, §11.5, §12;
// docs/interpolation.md "Arc").
//
// Coordinates are relative to the centre: the caller passes start - centre and end - centre.
// R2 = sx^2 + sy^2 (exact). Each call to next() makes one 8-connected move (Chebyshev distance 1):
//
//  1. Circle phase. From the current raster point p = (x, y) the driving axis is the one the
//     tangent runs along more (x when |y| > |x|, y when |x| > |y|; on the diagonal the axis whose
//     |coordinate| is falling, i.e. the octant being entered). It moves one step along the
//     tangent (CW tangent (y, -x), CCW (-y, x)). The minor coordinate m (sign s, M = |m|) becomes
//     s*V, V in {M-1, M, M+1}, the one whose half-open cell [V-1/2, V+1/2) holds the circle at the
//     new driving coordinate d', decided by the sign of the midpoint function scaled by 4:
//         g(u) = (2d')^2 + u^2 - 4*R2 at u = 2M-1 and 2M+1     [T: seed §3.3 eq. 2-13 corrected]
//     (g is odd, never 0: there are no midpoint ties). So each visited point lies within 1/2 step
//     of the circle along the minor axis, hence radially too: |sqrt(x^2+y^2) - sqrt(R2)| < 1/2.
//  2. The circle phase stops at the first point P whose angular position reaches or passes the
//     end's: with Q the previous point and E the end, E lies in the angular interval (Q, P] in the
//     turning direction: CCW: cross(Q,E) > 0 && cross(E,P) >= 0; CW: cross(Q,E) < 0 &&
//     cross(E,P) <= 0 (cross(A,B) = Ax*By - Ay*Bx; every move turns by less than 180 degrees).
//     The start is never tested, so an end on the start's ray (end == start included) is a full
//     circle. It also stops, as a guard, after circle_limit() = 8*isqrt(R2) + 8 moves (a full
//     circle needs fewer, docs/interpolation.md; the tests show the guard never fires).
//  3. Tail phase: a Line (line.hpp) from P to E, so the arc ends EXACTLY at the end point even
//     when E is not on the rasterised circle (G-code end points are rounded). The thesis's loop
//     stops only on equality with the end point and can run forever (seed §3.3, §11.5).
//
// Ranges: |coordinates| <= kMaxCoord = 2^20 (52 m at 20 steps/mm); R2 <= 2^41 (int64);
// visited points |x|, |y| <= isqrt(R2) + 1 < 2^21; g's terms <= (2*(2^20.5 + 2))^2 < 2^44
// (int64); cross products < 2^43 (int64). The tail's delta < 2^20 + 2^21 < Line::kMaxDelta.
// max_moves() = circle_limit() + isqrt(R2) + 1 + max(|ex|, |ey|) < 2^24 bounds the total:
// the tail starts within isqrt(R2) + 1 of the centre in each axis. The tests also check the
// tighter tail bound of docs/interpolation.md (in terms of |r_end - r_start|).
#pragma once

#include <array>
#include <cstdint>

#include "core/intmath/isqrt.hpp"
#include "core/xy/interp/error.hpp"
#include "core/xy/interp/line.hpp"

namespace ap::xy_interp {

enum class Turn : uint8_t { Cw, Ccw };

// floor(sqrt(v)) for v < 2^62: < 2^31, so it fits uint32_t (core/intmath).
[[nodiscard]] constexpr uint32_t isqrt64(uint64_t v) { return static_cast<uint32_t>(intmath::isqrt(v)); }

struct ArcResult;

class Arc {
 public:
  static constexpr int32_t kMaxCoord = int32_t{1} << 20;

  [[nodiscard]] static constexpr bool in_range(std::array<int32_t, 2> p) {
    return p[0] >= -kMaxCoord && p[0] <= kMaxCoord && p[1] >= -kMaxCoord && p[1] <= kMaxCoord;
  }

  // Typed refusal: CoordOutOfRange, ZeroRadius (start == centre), EndAtCentre (end == centre);
  // a refused arc is the default Arc: done() at (0, 0), no moves.
  [[nodiscard]] static constexpr ArcResult make(std::array<int32_t, 2> start, std::array<int32_t, 2> end, Turn turn);

  constexpr Arc() = default;

  [[nodiscard]] constexpr bool done() const { return phase_ == Phase::Done; }
  [[nodiscard]] constexpr bool on_tail() const { return phase_ == Phase::Tail; }
  [[nodiscard]] constexpr uint32_t circle_limit() const { return limit_; }
  [[nodiscard]] constexpr uint32_t max_moves() const { return limit_ + tail_limit_; }
  [[nodiscard]] constexpr uint32_t moves_made() const { return made_; }
  [[nodiscard]] constexpr uint32_t circle_moves() const { return circle_made_; }
  // Relative to the centre.
  [[nodiscard]] constexpr std::array<int32_t, 2> position() const { return {x_, y_}; }

  // The move to the next point, each component in {-1, 0, 1}; zeros once done().
  constexpr std::array<int8_t, 2> next() {
    if (phase_ == Phase::Done) {
      return {0, 0};
    }
    ++made_;
    if (phase_ == Phase::Circle) {
      const int32_t qx = x_;
      const int32_t qy = y_;
      circle_step();
      ++circle_made_;
      if (passes_end(qx, qy) || circle_made_ == limit_) {
        start_tail();
      }
      return {static_cast<int8_t>(x_ - qx), static_cast<int8_t>(y_ - qy)};
    }
    const std::array<int8_t, 3> m = tail_.next();
    x_ += m[0];
    y_ += m[1];
    if (tail_.done()) {
      phase_ = Phase::Done;
    }
    return {m[0], m[1]};
  }

 private:
  enum class Phase : uint8_t { Circle, Tail, Done };

  static constexpr int64_t cross(int64_t ax, int64_t ay, int64_t bx, int64_t by) { return ax * by - ay * bx; }
  static constexpr int32_t abs32(int32_t v) { return v < 0 ? -v : v; }  // |v| < 2^22 here

  // E in (Q, P] in the turning direction (header comment, step 2).
  [[nodiscard]] constexpr bool passes_end(int32_t qx, int32_t qy) const {
    const int64_t qe = cross(qx, qy, ex_, ey_);
    const int64_t ep = cross(ex_, ey_, x_, y_);
    return turn_ == Turn::Ccw ? (qe > 0 && ep >= 0) : (qe < 0 && ep <= 0);
  }

  // The minor coordinate at driving coordinate d (header comment, step 1).
  [[nodiscard]] constexpr int32_t minor_at(int32_t d, int32_t m) const {
    const int64_t dd = 2 * static_cast<int64_t>(d);
    const int64_t base = dd * dd - 4 * r2_;
    const int64_t big = m < 0 ? -static_cast<int64_t>(m) : m;
    const int64_t below = 2 * big - 1;  // the midpoint M - 1/2, doubled
    const int64_t above = 2 * big + 1;  // the midpoint M + 1/2, doubled
    int64_t v = big;
    if (big >= 1 && base + below * below > 0) {  // the circle runs inside M - 1/2
      v = big - 1;
    } else if (base + above * above < 0) {  // the circle runs outside M + 1/2
      v = big + 1;
    }
    return static_cast<int32_t>(m < 0 ? -v : v);
  }

  constexpr void circle_step() {
    const int32_t tx = turn_ == Turn::Cw ? y_ : -y_;
    const int32_t ty = turn_ == Turn::Cw ? -x_ : x_;
    const int32_t ax = abs32(x_);
    const int32_t ay = abs32(y_);
    // The diagonal: drive the axis whose |coordinate| is falling (the octant being entered).
    const bool drive_x = ay != ax ? ay > ax : ((tx > 0) != (x_ > 0));
    if (drive_x) {
      x_ += tx > 0 ? 1 : -1;
      y_ = minor_at(x_, y_);
    } else {
      y_ += ty > 0 ? 1 : -1;
      x_ = minor_at(y_, x_);
    }
  }

  constexpr void start_tail() {
    tail_ = Line{{ex_ - x_, ey_ - y_, 0}};
    phase_ = tail_.done() ? Phase::Done : Phase::Tail;
  }

  int64_t r2_ = 0;         // [1, 2^41]
  int32_t x_ = 0;          // current point, relative to the centre
  int32_t y_ = 0;
  int32_t ex_ = 0;         // end, relative to the centre, [-2^20, 2^20]
  int32_t ey_ = 0;
  uint32_t limit_ = 0;       // circle_limit()
  uint32_t tail_limit_ = 0;  // isqrt(R2) + 1 + max(|ex|, |ey|)
  uint32_t made_ = 0;        // moves made, <= max_moves()
  uint32_t circle_made_ = 0; // circle-phase moves, <= limit_
  Line tail_{};
  Turn turn_ = Turn::Cw;
  Phase phase_ = Phase::Done;
};

struct ArcResult {
  Arc arc;
  Error error;
};

constexpr ArcResult Arc::make(std::array<int32_t, 2> start, std::array<int32_t, 2> end, Turn turn) {
  if (!in_range(start) || !in_range(end)) {
    return {Arc{}, Error::CoordOutOfRange};
  }
  if (start[0] == 0 && start[1] == 0) {
    return {Arc{}, Error::ZeroRadius};
  }
  if (end[0] == 0 && end[1] == 0) {
    return {Arc{}, Error::EndAtCentre};
  }
  Arc a;
  a.r2_ = static_cast<int64_t>(start[0]) * start[0] + static_cast<int64_t>(start[1]) * start[1];
  a.x_ = start[0];
  a.y_ = start[1];
  a.ex_ = end[0];
  a.ey_ = end[1];
  a.turn_ = turn;
  const uint32_t r = isqrt64(static_cast<uint64_t>(a.r2_));
  a.limit_ = 8 * r + 8;
  a.tail_limit_ = r + 1 + static_cast<uint32_t>(abs32(end[0]) > abs32(end[1]) ? abs32(end[0]) : abs32(end[1]));
  a.phase_ = Phase::Circle;
  return {a, Error::None};
}

}  // namespace ap::xy_interp
