#pragma once
// Arithmetic written ONCE over a numeric policy, so the same text is instantiated two ways:
//   Sem::Bv   bit-precise two's-complement (bvadd/bvmul/bvsdiv/bvsrem), the semantics of the
//             C++ code;
//   Sem::Int  mathematical integers (QF_NIA), where Z3 can reason about division and
//             products. Every operation records a side condition "the exact result lies in
//             the C++ type's range" (and, for division, "dividend >= 0, divisor > 0", where
//             C++ truncation equals SMT floor division). Proving all side conditions proves that
//             both instantiations compute the same values, so lemmas proved in Int hold for the
//             Bv (= C++) terms. A profile's encodings of its core are written over it
//             (docs/proofs.md).
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <z3++.h>

namespace ap::model::smt {

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

}  // namespace ap::model::smt
