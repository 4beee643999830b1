// The braking kernels of the speed law (docs/motion.md §5 "Speed law, DD, and stopping exactly
// at the target"): the discrete deceleration distance D(v) and the largest safe speed in a
// tick's range. The only nonlinear arithmetic of the axis, in a file of their own because the
// proofs mirror exactly these two functions, once, over two semantics
// (models/xy/smt/axis_kernels.hpp), and prove their ranges apart from step().
#include "core/xy/axis/axis.hpp"

#include "kernels.hpp"

namespace ap::xy_axis {

int64_t stop_distance_fine(int32_t v, int32_t v_start_fine, int32_t accel) {
  if (v <= v_start_fine || accel <= 0) {
    return 0;
  }
  // m = number of braking ticks still above the start speed: k*a < v - s  <=>  k <= (v-s-1)/a.
  // a*m < v <= 1e9 and m+1 <= 1e9+1, so both products stay below 1.1e18 < 2^63; m*(m+1) is even.
  const int64_t vv = v;
  const int64_t a = accel;
  const int64_t m = (vv - v_start_fine - 1) / a;
  return m * vv - (a * m) * (m + 1) / 2;
}

// The highest speed in [lo, hi] from which the axis can still stop before the bound, or `lo`
// if none can (a retarget closer than the stopping distance: the axis overruns and returns).
// Braking along this exact fit instead of a fixed a-per-tick ramp leaves < 1 tick of creep at
// the start speed before the target, so moves end within a few ticks of the ideal profile.
//
// f(x) = x + D(x) is increasing. For x in piece m (x - s - 1 in [m*a, (m+1)*a - 1]),
// f(x) = (m+1)*x - a*m*(m+1)/2, linear, so the largest x with f(x) < room in that piece is
// floor((room - 1 + a*m*(m+1)/2) / (m+1)). hi - lo <= 2a, so at most 3 pieces matter: a fixed,
// loop-free unrolling. Ranges: room <= 2e15, a*m*(m+1)/2 <= 1e18: the sum stays < 2^63.
int32_t best_fit(int32_t lo, int32_t hi, int64_t room, int32_t s_fine, int32_t accel) {
  int32_t best = lo;
  if (lo <= s_fine) {
    best = hi < s_fine ? hi : s_fine;
  }
  const int64_t a = accel;
  const int64_t base = (lo > s_fine ? static_cast<int64_t>(lo) : static_cast<int64_t>(s_fine) + 1) - s_fine - 1;
  const int64_t m0 = base / a;
  const auto piece = [&](int64_t m) {
    const int64_t p_lo = s_fine + 1 + m * a;
    const int64_t p_hi = s_fine + (m + 1) * a;
    const int64_t num = room - 1 + (a * m) * (m + 1) / 2;
    if (num < 0) {
      return;
    }
    int64_t x = num / (m + 1);
    x = x < p_hi ? x : p_hi;
    x = x < hi ? x : static_cast<int64_t>(hi);
    if (x >= p_lo && x >= lo && x > best) {
      best = static_cast<int32_t>(x);
    }
  };
  piece(m0);
  piece(m0 + 1);
  piece(m0 + 2);
  return best;
}

}  // namespace ap::xy_axis
