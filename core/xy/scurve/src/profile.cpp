// The S-curve planner and stepper (docs/scurve.md; seed-003.md §5.4 for the segment pattern
// and the vanishing rules, §9 for "deceleration starts only at a = 0").
#include "core/xy/scurve/profile.hpp"

namespace ap::xy_scurve {
namespace {

constexpr uint64_t kU64Max = ~uint64_t{0};

// min(a * b, 2^64 - 1): the planner compares saturated products with bounds far below 2^63.
constexpr uint64_t mul_sat(uint64_t a, uint64_t b) {
  if (a != 0 && b > kU64Max / a) return kU64Max;
  return a * b;
}

// floor(sqrt(x)) for x <= 2^62.
constexpr uint64_t isqrt(uint64_t x) {
  uint64_t lo = 0;
  uint64_t hi = uint64_t{1} << 31;
  while (lo < hi) {  // invariant: lo^2 <= x, (hi + 1)^2 > x
    const uint64_t mid = lo + (hi - lo + 1) / 2;
    if (mid * mid <= x) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

// The no-cruise distance of a symmetric profile, normalised: Tj (Tj + Tc) (2 Tj + Tc),
// i.e. peak speed times the ramp time (seed §5.4: Sa = V Ta / 2, twice). Saturating.
constexpr uint64_t ramp_distance(uint64_t tj, uint64_t tc) { return mul_sat(tj * (tj + tc), 2 * tj + tc); }

PlanResult fail(Error e) { return PlanResult{Plan{}, e}; }

uint8_t first_from(const std::array<uint32_t, kSegments>& len, unsigned from) {
  unsigned i = from;
  while (i < kSegments && len[i] == 0) ++i;
  return static_cast<uint8_t>(i);
}

const std::array<uint32_t, kSegments>& lengths(const Plan& p, const State& s) { return s.stopping ? s.stop_len : p.len; }

}  // namespace

uint64_t mul_div_floor(uint64_t a, uint64_t b, uint64_t c) {
  // 128-bit product hi:lo from 32-bit halves.
  const uint64_t a0 = a & 0xFFFFFFFFU;
  const uint64_t a1 = a >> 32;
  const uint64_t b0 = b & 0xFFFFFFFFU;
  const uint64_t b1 = b >> 32;
  const uint64_t p00 = a0 * b0;
  const uint64_t p01 = a0 * b1;
  const uint64_t p10 = a1 * b0;
  const uint64_t p11 = a1 * b1;
  const uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFU) + (p10 & 0xFFFFFFFFU);
  const uint64_t lo = (p00 & 0xFFFFFFFFU) | (mid << 32);
  const uint64_t hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
  // Restoring division, one bit at a time (traces only; moves_at() needs no 128 bits).
  uint64_t rem = 0;
  uint64_t q = 0;
  for (int i = 127; i >= 0; --i) {
    const uint64_t bit = i >= 64 ? (hi >> (i - 64)) & 1U : (lo >> i) & 1U;
    const bool carry = (rem >> 63) != 0;
    rem = (rem << 1) | bit;
    if (carry || rem >= c) {
      rem -= c;
      if (i < 64) q |= uint64_t{1} << i;
    }
  }
  return q;
}

PlanResult plan(uint32_t moves, const Limits& lim) {
  const int64_t v = lim.v_max;
  const int64_t a = lim.a_max;
  const int64_t j = lim.j_max;
  if (v < 1 || v > kMaxVelocity || a < 1 || j < 1 || j > kMaxJerk) return fail(Error::BadLimits);
  // A jerk phase shorter than one tick cannot be represented (docs/scurve.md "Ranges").
  if (j > 1000 * a || j > 1000000 * v) return fail(Error::BadLimits);
  if (moves > kMaxMoves) return fail(Error::TooLong);
  if (moves == 0) return PlanResult{Plan{}, Error::None};

  // In normalised units (jerk J per tick^3) a distance D is D * J / 10^9 moves; the profile
  // must reach `moves`: D >= target = ceil(moves * 10^9 / J).
  const uint64_t uj = static_cast<uint64_t>(j);
  const uint64_t target = (uint64_t{moves} * 1000000000ULL + uj - 1) / uj;
  if (target > static_cast<uint64_t>(kMaxDistance)) return fail(Error::TooLong);

  // Ramp durations rounded DOWN so that at jerk J: peak a = Tj J <= a_max, i.e.
  // Tj <= a_max 1000 / J; peak v = Tj (Tj + Tc) J <= v_max, i.e. Tj (Tj + Tc) <= vcap.
  const uint64_t tj_a = static_cast<uint64_t>(a) * 1000U / uj;
  const uint64_t vcap = static_cast<uint64_t>(v) * 1000000U / uj;
  const uint64_t tj_v = isqrt(vcap);
  uint64_t tj = 0;
  uint64_t tc = 0;
  if (tj_v < tj_a) {
    tj = tj_v;  // V J < A^2: a_max is never reached, segments 2 and 6 vanish (seed §5.4)
  } else {
    tj = tj_a;
    tc = vcap / tj - tj;
  }
  const uint64_t vpk = tj * (tj + tc);
  uint64_t tv = 0;
  const uint64_t full = ramp_distance(tj, tc);
  if (full <= target) {
    tv = (target - full + vpk - 1) / vpk;  // cruise rounded UP: D >= target, sigma <= 1
  } else if (ramp_distance(tj, 0) >= target) {
    // Short path, pure jerk (seed §5.4 v_p = (L^2 J / 4)^(1/3)): the shortest Tj that reaches.
    uint64_t lo = 1;
    uint64_t hi = tj;
    while (lo < hi) {
      const uint64_t mid = lo + (hi - lo) / 2;
      if (ramp_distance(mid, 0) >= target) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    tj = lo;
    tc = 0;
  } else {
    // Short path with a constant-acceleration segment: the shortest Tc that reaches.
    uint64_t lo = 0;
    uint64_t hi = tc;
    while (lo < hi) {
      const uint64_t mid = lo + (hi - lo) / 2;
      if (ramp_distance(tj, mid) >= target) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    tc = lo;
  }
  const uint64_t d = ramp_distance(tj, tc) + tj * (tj + tc) * tv;
  if (d > static_cast<uint64_t>(kMaxDistance)) return fail(Error::TooLong);
  const uint64_t total = 4 * tj + 2 * tc + tv;
  if (total > kMaxTicks) return fail(Error::TooLong);

  Plan p;
  p.moves = moves;
  const auto t32 = static_cast<uint32_t>(tj);
  const auto c32 = static_cast<uint32_t>(tc);
  p.len = {t32, c32, t32, static_cast<uint32_t>(tv), t32, c32, t32};
  p.tj = static_cast<int64_t>(tj);
  p.v2_peak = static_cast<int64_t>(2 * tj * (tj + tc));
  p.p6_end = static_cast<int64_t>(6 * d);
  p.total_ticks = total;
  return PlanResult{p, Error::None};
}

State start(const Plan& p) {
  State s;
  s.seg = first_from(p.len, 0);
  return s;
}

int8_t next_jerk(const Plan& p, const State& s) {
  (void)p;
  if (s.seg >= kSegments) return 0;
  return s.stopping ? kStopJerk[s.seg] : kPlanJerk[s.seg];
}

State step(const Plan& p, const State& s) {
  if (s.seg >= kSegments) return s;
  const auto& len = lengths(p, s);
  State n = s;
  n.k = advance(s.k, next_jerk(p, s));
  n.tick = s.tick + 1;
  if (n.tick >= len[s.seg]) {
    n.tick = 0;
    n.seg = first_from(len, s.seg + 1U);
  }
  return n;
}

bool finished(const Plan& p, const State& s) {
  (void)p;
  return s.seg >= kSegments;
}

uint32_t moves_at(const Plan& p, const State& s) {
  if (p.p6_end <= 0 || s.k.p6 <= 0) return 0;
  // moves <= 2^20 and P6 <= P6_end <= 6 * 2^41: the product is below 2^64.
  return static_cast<uint32_t>(uint64_t{p.moves} * static_cast<uint64_t>(s.k.p6) / static_cast<uint64_t>(p.p6_end));
}

State request_stop(const Plan& p, const State& s) {
  // Finished, already stopping, or decelerating (segment 4 on: a <= 0 and the planned
  // deceleration is itself the jerk-limited stop, ending at the planned end).
  if (s.seg >= kSegments || s.stopping || s.seg >= 4) return s;
  const int64_t k0 = s.k.a;  // >= 0 in segments 0..3: ramped down first (seed §9: decelerate from a = 0)
  const Exact at_zero = advance_n(s.k, -1, k0);
  const int64_t half = at_zero.v2 / 2;  // V2 is even where A = 0 (docs/scurve.md "Stop")
  State n = s;
  n.stopping = true;
  n.tick = 0;
  if (half == 0) {  // at rest: nothing to do
    n.stop_len = {};
    n.seg = kSegments;
    return n;
  }
  // Main hump: -1 for k1, 0 for c1, +1 for k1 removes k1 (k1 + c1) of v; |A| <= k1 <= Tj.
  const int64_t k1 = static_cast<int64_t>(isqrt(static_cast<uint64_t>(half))) < p.tj
                         ? static_cast<int64_t>(isqrt(static_cast<uint64_t>(half)))
                         : p.tj;
  const int64_t c1 = (half - k1 * k1) / k1;
  const int64_t r = half - k1 * (k1 + c1);  // 0 <= r < k1: removed by a hump of k = 1, c = r - 1
  const int64_t k2 = r > 0 ? 1 : 0;
  const int64_t c2 = r > 0 ? r - 1 : 0;
  n.stop_len = {static_cast<uint32_t>(k0 + k1), static_cast<uint32_t>(c1), static_cast<uint32_t>(k1),
                static_cast<uint32_t>(k2), static_cast<uint32_t>(c2), static_cast<uint32_t>(k2), 0U};
  Exact e = s.k;
  for (unsigned i = 0; i < kSegments; ++i) e = advance_n(e, kStopJerk[i], n.stop_len[i]);
  // The stop must not end past the planned end: then the plan's own deceleration stops sooner.
  if (e.p6 > p.p6_end || e.v2 != 0 || e.a != 0) return s;
  n.seg = first_from(n.stop_len, 0);
  return n;
}

Kinematics kinematics(const Plan& p, const State& s) {
  Kinematics k;
  if (p.p6_end <= 0) return k;
  const auto den = static_cast<uint64_t>(p.p6_end);
  const uint64_t m = p.moves;
  const auto signed_scale = [&](int64_t x, uint64_t factor) {
    const uint64_t mag = x < 0 ? static_cast<uint64_t>(-x) : static_cast<uint64_t>(x);
    const auto q = static_cast<int64_t>(mul_div_floor(mag * m, factor, den));
    return x < 0 ? -q : q;
  };
  k.jerk_milli = signed_scale(next_jerk(p, s), 6000000000000ULL);
  k.accel_milli = signed_scale(s.k.a, 6000000000ULL);
  k.vel_milli = signed_scale(s.k.v2, 3000000ULL);
  k.pos_milli = signed_scale(s.k.p6, 1000ULL);
  return k;
}

}  // namespace ap::xy_scurve
