#pragma once
// The nonlinear arithmetic kernels of core/xy/axis written ONCE over a numeric policy, so the
// same text is instantiated two ways:
//   Sem::Bv   bit-precise int64 two's-complement (bvadd/bvmul/bvsdiv/bvsrem), the semantics of
//             the C++ code; used by the step encoding and checked against step() by the
//             conformance property (properties/xy/smt/smt_conformance_test.cpp);
//   Sem::Int  mathematical integers (QF_NIA), where Z3 can reason about division and
//             products. Every operation records a side condition "the exact result lies in
//             the C++ type's range" (and, for division, "dividend >= 0, divisor > 0", where
//             C++ truncation equals SMT floor division). Proving all side conditions
//             (obligation axis.overflow.kernels) proves that both instantiations compute the
//             same values, so lemmas proved in Int hold for the Bv (= C++) kernels.
//
// MIRRORS core/xy/axis/src/kernels.cpp stop_distance_fine() and best_fit(), and
// core/xy/axis/include/core/xy/axis/step_timer.hpp step_timer(), line for line. They MUST change
// together; the conformance property fails when they do not.
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <z3++.h>

#include "models/smt/arith.hpp"

namespace ap::model::smt::xy_axis {

using smt::Arith;
using smt::Check;
using smt::Checks;
using smt::Sem;

// ---- stop_distance_fine(v, v_start_fine, accel) ------------------------------------------
// Arguments are the int32 values already widened to 64 bits (Arith::widen32).
inline z3::expr stop_distance_fine(const Arith& ar, const z3::expr& v, const z3::expr& s, const z3::expr& accel) {
  const z3::expr zero = ar.lit(0);
  const z3::expr early = v <= s || accel <= zero;
  const Arith in = ar.under(!early);
  const z3::expr vv = v;
  const z3::expr a = accel;
  const z3::expr m = in.div(in.sub(in.sub(vv, s, "dd.v-s"), ar.lit(1), "dd.v-s-1"), a, "dd.m");
  const z3::expr am = in.mul(a, m, "dd.a*m");
  const z3::expr r = in.sub(in.mul(m, vv, "dd.m*v"),
                            in.div(in.mul(am, in.add(m, ar.lit(1), "dd.m+1"), "dd.a*m*(m+1)"), ar.lit(2), "dd./2"),
                            "dd.result");
  return z3::ite(early, zero, r);
}

// ---- best_fit(lo, hi, room, s_fine, accel) -----------------------------------------------
// lo, hi, s, accel: widened int32; room: int64. Returns the widened int32 result.
// `pieces` (optional) receives each unrolled piece's terms, for the piece lemma.
struct PieceTerms {
  z3::expr m, p_lo, p_hi, num, q, x;  // q: num / (m + 1) before the clamps; x: after them
};
inline z3::expr best_fit(const Arith& ar, const z3::expr& lo, const z3::expr& hi, const z3::expr& room,
                         const z3::expr& s, const z3::expr& accel, std::vector<PieceTerms>* pieces = nullptr) {
  z3::expr best = z3::ite(lo <= s, z3::ite(hi < s, hi, s), lo);
  const z3::expr a = accel;
  const z3::expr one = ar.lit(1);
  // (lo > s ? lo : s + 1) - s - 1, all int64 after the first widening.
  const z3::expr base =
      ar.sub(ar.sub(z3::ite(lo > s, lo, ar.add(s, one, "bf.s+1")), s, "bf.base-s"), one, "bf.base");
  const z3::expr m0 = ar.div(base, a, "bf.m0");
  for (int k = 0; k < 3; ++k) {
    const std::string p = "bf.piece" + std::to_string(k) + ".";
    const z3::expr m = k == 0 ? m0 : ar.add(m0, ar.lit(k), p + "m");
    const z3::expr p_lo = ar.add(ar.add(s, one, p + "s+1", true), ar.mul(m, a, p + "m*a"), p + "p_lo");
    const z3::expr p_hi = ar.add(s, ar.mul(ar.add(m, one, p + "m+1"), a, p + "(m+1)*a"), p + "p_hi");
    const z3::expr num = ar.add(ar.sub(room, one, p + "room-1"),
                                ar.div(ar.mul(ar.mul(a, m, p + "a*m"), ar.add(m, one, p + "m+1'"), p + "a*m*(m+1)"),
                                       ar.lit(2), p + "/2"),
                                p + "num");
    const Arith in = ar.under(!(num < ar.lit(0)));
    const z3::expr q = in.div(num, in.add(m, one, p + "m+1''"), p + "x");
    z3::expr x = z3::ite(q < p_hi, q, p_hi);
    x = z3::ite(x < hi, x, hi);
    if (pieces != nullptr) pieces->push_back({m, p_lo, p_hi, num, q, x});
    best = z3::ite(!(num < ar.lit(0)) && x >= p_lo && x >= lo && x > best, x, best);
  }
  return best;
}

// ---- step_timer(f_hz) (uint64) ---------------------------------------------------------
struct TimerTerms {
  z3::expr psc;  // before the uint16 cast
  z3::expr arr;
};
inline TimerTerms step_timer(const Arith& ar, const z3::expr& f) {
  const z3::expr clk = ar.ulit(80'000'000);
  const z3::expr psc = ar.div(ar.sub(clk, ar.ulit(1), "timer.clk-1"),
                              ar.mul(f, ar.add(ar.ulit(65'535), ar.ulit(1), "timer.65536"), "timer.f*65536"), "timer.psc");
  const z3::expr arr = ar.sub(ar.div(clk, ar.mul(f, ar.add(psc, ar.ulit(1), "timer.psc+1"), "timer.f*(psc+1)"), "timer.q"),
                              ar.ulit(1), "timer.arr");
  return {psc, arr};
}

}  // namespace ap::model::smt::xy_axis
