// Bresenham line obligations (docs/interpolation.md "Proof"), over the core's per-axis step
// Line::axis_step (core/xy/interp/line.hpp) as it computes it in int32. interp_axis_step_err and
// interp_axis_step_moves state that step as Z3 terms; properties/xy/interp/proof_test.cpp checks
// them against the core on random concrete states and along whole lines, so the proofs speak
// about the code that runs.
//
// One axis of a line: n = moves() (the major |delta|), a = |delta_i| in [0, n], k moves made,
// y = |position_i| and err the decision variable. Every axis of a 2- or 3-axis line runs this
// same step with the shared n (the major axis with a = n), and no axis reads another's state,
// so the per-axis claims below hold for every axis of every 2-D and 3-D line in range.
#include <cstdint>

#include "core/xy/interp/line.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

// Line::axis_step as terms over 32-bit signed values (int32 in the core).
z3::expr interp_axis_step_err(z3::context& c, const z3::expr& n, const z3::expr& a, const z3::expr& err) {
  const z3::expr e = err + c.bv_val(2, 32) * a;
  return z3::ite(z3::sge(e, n), e - c.bv_val(2, 32) * n, e);
}

z3::expr interp_axis_step_moves(z3::context& c, const z3::expr& n, const z3::expr& a, const z3::expr& err) {
  return z3::sge(err + c.bv_val(2, 32) * a, n);
}

namespace {

constexpr int32_t kMax = ap::xy_interp::Line::kMaxDelta;

struct Axis {
  z3::context& c;
  z3::expr n, a, k, y, err;
  explicit Axis(z3::context& ctx)
      : c(ctx), n(ctx.bv_const("n", 32)), a(ctx.bv_const("a", 32)), k(ctx.bv_const("k", 32)),
        y(ctx.bv_const("y", 32)), err(ctx.bv_const("err", 32)) {}
  z3::expr v(int64_t x) const { return c.bv_val(x, 32); }
  // The line's range: 1 <= n <= 2^24, 0 <= a <= n.
  z3::expr line() const { return z3::sge(n, v(1)) && z3::sle(n, v(kMax)) && z3::sge(a, v(0)) && z3::sle(a, n); }
  z3::expr err_range(const z3::expr& e) const { return z3::sge(e, -n) && z3::slt(e, n); }
  // 2*(k*a - n*y), exactly: the operands are in [0, 2^24], the products < 2^48, in 64 bits.
  z3::expr exact(const z3::expr& kk, const z3::expr& yy) const { return exact64(z3::zext(kk, 32), z3::zext(yy, 32)); }
  z3::expr exact64(const z3::expr& kk, const z3::expr& yy) const {
    return c.bv_val(2, 64) * (kk * z3::zext(a, 32) - z3::zext(n, 32) * yy);
  }
  // The invariant between calls: 0 <= y <= k <= n (y counts the axis's moves), err in [-n, n) and
  // err == 2*(k*a - n*y) exactly. (y <= a follows: y never falls and ends at a, exact_end.)
  z3::expr inv(const z3::expr& kk, const z3::expr& yy, const z3::expr& e) const {
    return z3::sge(yy, v(0)) && z3::sle(yy, kk) && z3::sle(kk, n) && err_range(e) && z3::sext(e, 32) == exact(kk, yy);
  }
  Shown shown() const { return {{"n", n}, {"a", a}, {"k", k}, {"y", y}, {"err", err}}; }
};

}  // namespace

void add_interp_obligations(ObligationList& out) {
  out.push_back({"interp.bresenham.decision_range",
                 "QF_BV 32-bit, the core's int32 arithmetic, for every n in [1, 2^24], a in [0, n], err in [-n, n): "
                 "Line::axis_step has no signed overflow (equal to the same step computed in 34 bits) and keeps "
                 "err in [-n, n)",
                 [](unsigned ms) {
                   Axis s(shared_context());
                   z3::context& c = s.c;
                   const z3::expr e2 = interp_axis_step_err(c, s.n, s.a, s.err);
                   const z3::expr moves = interp_axis_step_moves(c, s.n, s.a, s.err);
                   const auto x = [](const z3::expr& t) { return z3::sext(t, 2); };
                   const z3::expr we = x(s.err) + c.bv_val(2, 34) * x(s.a);
                   const z3::expr wide = z3::ite(z3::sge(we, x(s.n)), we - c.bv_val(2, 34) * x(s.n), we);
                   const z3::expr claim = z3::implies(s.line() && s.err_range(s.err),
                                                      x(e2) == wide && moves == z3::sge(we, x(s.n)) && s.err_range(e2));
                   return check_valid(c, claim, ms, s.shown());
                 }});
  out.push_back({"interp.bresenham.error_invariant",
                 "QF_BV (32-bit state, 64-bit products), induction over next(): for every n in [1, 2^24], a in [0, n] "
                 "the invariant 0 <= y <= k <= n, err in [-n, n), err == X(k, y) = 2*(k*a - n*y) holds at the start "
                 "(k = y = err = 0), and one step (k < n; the axis moves s = 0 or 1) keeps the ranges and changes err "
                 "by exactly 2a - 2n*s, which is X(k+1, y+s) - X(k, y) (the distributive law, proved here for all "
                 "64-bit values); so err == X holds after the step. Z3 times out on the substituted form (products "
                 "of two symbolic values), hence the two conjuncts",
                 [](unsigned ms) {
                   Axis s(shared_context());
                   z3::context& c = s.c;
                   const z3::expr moves = interp_axis_step_moves(c, s.n, s.a, s.err);
                   const z3::expr e2 = interp_axis_step_err(c, s.n, s.a, s.err);
                   const z3::expr y2 = s.y + z3::ite(moves, s.v(1), s.v(0));
                   const z3::expr k2 = s.k + s.v(1);
                   const z3::expr two = c.bv_val(2, 64);
                   const z3::expr change = two * z3::zext(s.a, 32) - z3::ite(moves, two * z3::zext(s.n, 32), c.bv_val(0, 64));
                   const z3::expr ranges = z3::sge(s.y, s.v(0)) && z3::sle(s.y, s.k) && z3::sle(s.k, s.n) && s.err_range(s.err);
                   // ... and the 32-bit k + 1 and y + s do not wrap (they equal the 64-bit sums below).
                   const z3::expr ranges2 = z3::sge(y2, s.v(0)) && z3::sle(y2, k2) && z3::sle(k2, s.n) && s.err_range(e2) &&
                                            z3::zext(k2, 32) == z3::zext(s.k, 32) + c.bv_val(1, 64) &&
                                            z3::zext(y2, 32) == z3::zext(s.y, 32) + z3::ite(moves, c.bv_val(1, 64), c.bv_val(0, 64));
                   const z3::expr base = s.inv(s.v(0), s.v(0), s.v(0));
                   const z3::expr step = z3::implies(ranges && z3::slt(s.k, s.n),
                                                     ranges2 && z3::sext(e2, 32) == z3::sext(s.err, 32) + change);
                   // The distributive law for either value of s (a free Boolean: Z3 proves the bare ring
                   // identity at once, but not through the decision term).
                   const z3::expr any_s = c.bool_const("s");
                   const z3::expr any_change = two * z3::zext(s.a, 32) - z3::ite(any_s, two * z3::zext(s.n, 32), c.bv_val(0, 64));
                   const z3::expr k64 = c.bv_const("k64", 64);
                   const z3::expr y64 = c.bv_const("y64", 64);
                   const z3::expr distributive =
                       s.exact64(k64 + c.bv_val(1, 64), y64 + z3::ite(any_s, c.bv_val(1, 64), c.bv_val(0, 64))) ==
                       s.exact64(k64, y64) + any_change;
                   return check_valid(c, z3::implies(s.line(), base && step) && distributive, ms, s.shown());
                 }});
  out.push_back({"interp.bresenham.half_step_bound",
                 "QF_BV, for every n in [1, 2^24]: a decision variable err in [-n, n) equal to the exact cross-axis "
                 "value x = 2*(k*a - n*y) (as the invariant states) gives |x| <= n, i.e. |k*a/n - y| <= 1/2: the "
                 "minor axis is within 1/2 step of the ideal line at every major position (x is left free, so "
                 "this holds for every k, y, a)",
                 [](unsigned ms) {
                   Axis s(shared_context());
                   const z3::expr x = s.c.bv_const("exact", 64);
                   const z3::expr n64 = z3::zext(s.n, 32);
                   const z3::expr pre = z3::sge(s.n, s.v(1)) && z3::sle(s.n, s.v(kMax)) && s.err_range(s.err) &&
                                        z3::sext(s.err, 32) == x;
                   const z3::expr claim = z3::implies(pre, z3::sle(-n64, x) && z3::sle(x, n64));
                   return check_valid(s.c, claim, ms, {{"n", s.n}, {"err", s.err}, {"exact", x}});
                 }});
  out.push_back({"interp.bresenham.exact_end",
                 "QF_BV, for every n in [1, 2^24], a in [0, n]: the invariant at k = n (after moves() calls; done() "
                 "is k == n) implies y == a, so every axis ends exactly on its delta. Stated as the distributive law "
                 "X(n, y) = 2*(n*a - n*y) == 2*n*(a - y) (all 64-bit values) and, for every u in [0, n] (u = |a - y|, "
                 "a, y in [0, n]; 25-bit, products in 52 bits), 2*n*u <= n implies u == 0 (-n <= 2*n*(a-y) < n "
                 "gives 2*n*|a - y| <= n)",
                 [](unsigned ms) {
                   Axis s(shared_context());
                   z3::context& c = s.c;
                   const z3::expr distributive =
                       s.exact(s.n, s.y) == c.bv_val(2, 64) * z3::zext(s.n, 32) * (z3::zext(s.a, 32) - z3::zext(s.y, 32));
                   // |d| = u in [0, n]: 2*n*u <= n forces u == 0 (covers both signs of d:
                   // d >= 0 needs 2*n*d < n, d < 0 needs -n <= 2*n*d, i.e. 2*n*|d| <= n).
                   const z3::expr nn = c.bv_const("n25", 25);
                   const z3::expr u = c.bv_const("u", 25);
                   const z3::expr twice = c.bv_val(2, 52) * z3::zext(nn, 27) * z3::zext(u, 27);
                   const z3::expr only_zero = z3::implies(z3::uge(nn, c.bv_val(1, 25)) && z3::ule(nn, c.bv_val(kMax, 25)) &&
                                                              z3::ule(u, nn) && z3::ule(twice, z3::zext(nn, 27)),
                                                          u == c.bv_val(0, 25));
                   const z3::expr claim = distributive && only_zero;
                   return check_valid(c, claim, ms, {{"n", s.n}, {"a", s.a}, {"y", s.y}, {"n25", nn}, {"u", u}});
                 }});
  out.push_back({"interp.bresenham.major_axis_every_step",
                 "QF_BV 32-bit, for every n in [1, 2^24] and err in [-n, n): the major axis (a = n) moves on every "
                 "call and its err is unchanged (0 from the start)",
                 [](unsigned ms) {
                   Axis s(shared_context());
                   z3::context& c = s.c;
                   const z3::expr pre = z3::sge(s.n, s.v(1)) && z3::sle(s.n, s.v(kMax)) && s.err_range(s.err);
                   const z3::expr claim = z3::implies(pre, interp_axis_step_moves(c, s.n, s.n, s.err) &&
                                                               interp_axis_step_err(c, s.n, s.n, s.err) == s.err);
                   return check_valid(c, claim, ms, s.shown());
                 }});
}

}  // namespace ap::model::smt
