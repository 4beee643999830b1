// Bresenham line in 2 or 3 axes, integers only (seed-003.md §3.2, §12 "Interpolation";
// docs/interpolation.md "Line").
//
// The line runs from the origin to `delta` in moves() = max_i |delta_i| moves. Every call to
// next() advances the major axis (the one with the largest |delta_i|, lowest index on a tie)
// by one step and each minor axis by 0 or one step toward its end.
//
// Ranges (all proved or tested, docs/interpolation.md):
//   |delta_i| <= kMaxDelta = 2^24 (16 777 216 steps = 838 m at the thesis's 20 steps/mm);
//   n = moves() <= 2^24, 0 <= k (moves made) <= n, a_i = |delta_i| <= n;
//   per-axis decision variable err_i = 2*(k*a_i - n*y_i), y_i = |position_i|, kept in [-n, n)
//   (that is, the ideal minus the actual minor position lies in [-1/2, +1/2));
//   inside next() err_i + 2*a_i < 3n <= 3*2^24 < 2^31, so every quantity fits int32
//   (proved: interp.bresenham.decision_range).
//
// Tie rule [T, seed-003.md §3.2, the thesis's all-octant loop]: when the ideal minor position is
// exactly half-way (err_i + 2*a_i == n) the minor axis steps, i.e. it rounds half away from the
// start. That is what the thesis's MATLAB loop does ((0,0)->(4,1) passes (2,1)).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/xy/interp/error.hpp"

namespace ap::xy_interp {

struct LineResult;

class Line {
 public:
  static constexpr int32_t kMaxDelta = int32_t{1} << 24;

  // One axis's decision step (what next() does per axis; the proof's terms mirror it,
  // models/smt/src/interp_obligations.cpp). n = moves(), a = |delta_i|, err in [-n, n).
  struct AxisStep {
    int32_t err;
    bool moves;
  };
  [[nodiscard]] static constexpr AxisStep axis_step(int32_t n, int32_t a, int32_t err) {
    const int32_t e = err + 2 * a;  // < n + 2n <= 3*2^24
    if (e >= n) {                   // >= : a half-way tie steps (the tie rule above)
      return {e - 2 * n, true};
    }
    return {e, false};
  }

  [[nodiscard]] static constexpr bool valid(std::array<int32_t, 3> delta) {
    for (const int32_t d : delta) {
      if (d < -kMaxDelta || d > kMaxDelta) {
        return false;
      }
    }
    return true;
  }

  // The typed way in: an out-of-range delta gives a zero-length line and DeltaOutOfRange.
  [[nodiscard]] static constexpr LineResult make(std::array<int32_t, 3> delta);

  constexpr Line() = default;
  // Documented refusal without an error channel: an invalid delta (see valid()) makes a
  // zero-length line (moves() == 0, done()). Use make() to learn why.
  constexpr explicit Line(std::array<int32_t, 3> delta) {
    if (!valid(delta)) {
      return;
    }
    int32_t n = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      const int32_t d = delta[i];
      a_[i] = d < 0 ? -d : d;  // |d| <= 2^24: no overflow
      sign_[i] = static_cast<int8_t>(d > 0 ? 1 : (d < 0 ? -1 : 0));
      n = a_[i] > n ? a_[i] : n;
    }
    n_ = n;
  }

  [[nodiscard]] constexpr uint32_t moves() const { return static_cast<uint32_t>(n_); }
  [[nodiscard]] constexpr uint32_t moves_made() const { return static_cast<uint32_t>(k_); }
  [[nodiscard]] constexpr bool done() const { return k_ == n_; }

  // The move to the next point: each component in {-1, 0, 1}; zeros once done().
  constexpr std::array<int8_t, 3> next() {
    std::array<int8_t, 3> move{0, 0, 0};
    if (done()) {
      return move;
    }
    ++k_;
    for (std::size_t i = 0; i < 3; ++i) {
      // The major axis has a_i == n: err + 2n >= n always, so it steps every call and its
      // err stays 0. An unused axis has a_i == 0 and never steps.
      const AxisStep s = axis_step(n_, a_[i], err_[i]);
      err_[i] = s.err;
      if (s.moves) {
        pos_[i] += sign_[i];
        move[i] = sign_[i];
      }
    }
    return move;
  }

  // Relative to the start.
  [[nodiscard]] constexpr std::array<int32_t, 3> position() const { return pos_; }

 private:
  int32_t n_ = 0;  // moves(), [0, 2^24]
  int32_t k_ = 0;  // moves made, [0, n_]
  std::array<int32_t, 3> a_{};    // |delta_i|, [0, n_]
  std::array<int32_t, 3> err_{};  // [-n_, n_) between calls
  std::array<int32_t, 3> pos_{};  // sign_i * y_i, |pos_i| <= a_i
  std::array<int8_t, 3> sign_{};  // sign(delta_i)
};

struct LineResult {
  Line line;
  Error error;
};

constexpr LineResult Line::make(std::array<int32_t, 3> delta) {
  if (!valid(delta)) {
    return {Line{}, Error::DeltaOutOfRange};
  }
  return {Line{delta}, Error::None};
}

}  // namespace ap::xy_interp
