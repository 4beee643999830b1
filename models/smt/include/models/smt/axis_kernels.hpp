#pragma once
// The nonlinear arithmetic kernels of core/axis written ONCE over a numeric policy, so the
// same text is instantiated two ways:
//   Sem::Bv   bit-precise int64 two's-complement (bvadd/bvmul/bvsdiv/bvsrem), the semantics of
//             the C++ code; used by the step encoding and checked against step() by the
//             conformance property (properties/smt/smt_conformance_test.cpp);
//   Sem::Int  mathematical integers (QF_NIA), where Z3 can reason about division and
//             products. Every operation records a side condition "the exact result lies in
//             the C++ type's range" (and, for division, "dividend >= 0, divisor > 0", where
//             C++ truncation equals SMT floor division). Proving all side conditions
//             (obligation axis.overflow.kernels) proves that both instantiations compute the
//             same values, so lemmas proved in Int hold for the Bv (= C++) kernels.
//
// MIRRORS core/axis/src/axis.cpp stop_distance_fine() and best_fit(), and
// core/axis/include/core/axis/step_timer.hpp step_timer(), line for line. They MUST change
// together; the conformance property fails when they do not.
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <z3++.h>

namespace ap::model::smt::axis {

enum class Sem { Bv, Int };

// A recorded side condition: `cond` must hold whenever `guard` holds.
struct Check {
  std::string name;
  z3::expr guard;
  z3::expr cond;
};
using Checks = std::vector<Check>;

// Signed 64-bit arithmetic (or unsigned 64-bit with `unsig`), with side conditions.
struct Arith {
  z3::context& c;
  Sem sem;
  Checks* checks;
  z3::expr guard;  // the path condition under which the current code runs
  bool unsig = false;

  Arith(z3::context& ctx, Sem s, Checks* ch, const z3::expr& g, bool u = false)
      : c(ctx), sem(s), checks(ch), guard(g), unsig(u) {}

  [[nodiscard]] Arith under(const z3::expr& g) const { return Arith(c, sem, checks, guard && g, unsig); }

  [[nodiscard]] z3::expr lit(std::int64_t v) const {
    if (sem == Sem::Int) return c.int_val(v);
    return c.bv_val(v, 64);
  }
  [[nodiscard]] z3::expr ulit(std::uint64_t v) const {
    if (sem == Sem::Int) return c.int_val(v);
    return c.bv_val(v, 64);
  }
  // A 32-bit C++ value widened: sign (int32) or zero (uint32) extension in Bv.
  [[nodiscard]] z3::expr widen32(const z3::expr& e) const {
    if (sem == Sem::Int) return e;
    return unsig ? z3::zext(e, 32) : z3::sext(e, 32);
  }
  [[nodiscard]] z3::expr t_true() const { return c.bool_val(true); }

  void record(const std::string& name, const z3::expr& cond) const {
    if (checks != nullptr) checks->push_back({name, guard, cond});
  }
  // In Int: the exact result lies in [lo, hi] of the C++ type.
  void in_range(const std::string& name, const z3::expr& r, bool is32) const {
    if (sem != Sem::Int) return;
    if (unsig) {
      const std::uint64_t hi = is32 ? std::numeric_limits<std::uint32_t>::max() : std::numeric_limits<std::uint64_t>::max();
      record(name, r >= c.int_val(0) && r <= c.int_val(hi));
    } else {
      const std::int64_t lo = is32 ? std::numeric_limits<std::int32_t>::min() : std::numeric_limits<std::int64_t>::min();
      const std::int64_t hi = is32 ? std::numeric_limits<std::int32_t>::max() : std::numeric_limits<std::int64_t>::max();
      record(name, r >= c.int_val(lo) && r <= c.int_val(hi));
    }
  }
  // In Bv: the no-overflow predicates of the operation (redundant with the Int proof, but
  // they make the Bv encoding self-checking too).
  [[nodiscard]] z3::expr add(const z3::expr& a, const z3::expr& b, const std::string& n, bool is32 = false) const {
    const z3::expr r = a + b;
    in_range(n, r, is32);
    if (sem == Sem::Bv && !is32) record(n, z3::bvadd_no_overflow(a, b, !unsig) && (unsig ? t_true() : z3::bvadd_no_underflow(a, b)));
    if (sem == Sem::Bv && is32) record(n, fits32(r));
    return is32 ? wrap32(r) : r;
  }
  [[nodiscard]] z3::expr sub(const z3::expr& a, const z3::expr& b, const std::string& n, bool is32 = false) const {
    const z3::expr r = a - b;
    in_range(n, r, is32);
    if (sem == Sem::Bv && !is32) record(n, unsig ? z3::uge(a, b) : (z3::bvsub_no_overflow(a, b) && z3::bvsub_no_underflow(a, b, true)));
    if (sem == Sem::Bv && is32) record(n, fits32(r));
    return is32 ? wrap32(r) : r;
  }
  [[nodiscard]] z3::expr mul(const z3::expr& a, const z3::expr& b, const std::string& n, bool is32 = false) const {
    const z3::expr r = a * b;
    in_range(n, r, is32);
    if (sem == Sem::Bv && !is32) record(n, z3::bvmul_no_overflow(a, b, !unsig) && (unsig ? t_true() : z3::bvmul_no_underflow(a, b)));
    if (sem == Sem::Bv && is32) record(n, fits32(r));
    return is32 ? wrap32(r) : r;
  }
  // C++ '/': truncation toward zero.
  [[nodiscard]] z3::expr div(const z3::expr& a, const z3::expr& b, const std::string& n) const {
    if (sem == Sem::Int) {
      record(n, a >= c.int_val(0) && b > c.int_val(0));
      return a / b;
    }
    if (unsig) {
      record(n, b != ulit(0));
      return z3::udiv(a, b);
    }
    record(n, b != lit(0) && !(a == lit(std::numeric_limits<std::int64_t>::min()) && b == lit(-1)));
    return a / b;  // bvsdiv
  }
  // An int32 (uint32) result computed in 64 bits: what the 32-bit operation leaves, i.e. the
  // low 32 bits extended again (Bv). In Int the exact value, whose range is checked.
  [[nodiscard]] z3::expr wrap32(const z3::expr& r) const {
    if (sem == Sem::Int) return r;
    return unsig ? z3::zext(r.extract(31, 0), 32) : z3::sext(r.extract(31, 0), 32);
  }
  // In Bv with 32-bit operands computed in 64 bits: the int32 result range.
  [[nodiscard]] z3::expr fits32(const z3::expr& r) const {
    if (unsig) return z3::ule(r, ulit(std::numeric_limits<std::uint32_t>::max()));
    return r >= lit(std::numeric_limits<std::int32_t>::min()) && r <= lit(std::numeric_limits<std::int32_t>::max());
  }
  [[nodiscard]] z3::expr lt(const z3::expr& a, const z3::expr& b) const {
    return (sem == Sem::Bv && unsig) ? z3::ult(a, b) : a < b;
  }
  [[nodiscard]] z3::expr le(const z3::expr& a, const z3::expr& b) const {
    return (sem == Sem::Bv && unsig) ? z3::ule(a, b) : a <= b;
  }
};

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

}  // namespace ap::model::smt::axis
