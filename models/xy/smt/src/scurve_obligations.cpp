// The S-curve's obligations (docs/scurve.md "Proof"). step() of core/xy/scurve is stated here as
// terms over its state (segment, tick, A, V2) and the plan's segment lengths, with the jerk of
// each segment read from the core (kPlanJerk), so a change to the core's pattern is a change
// to what is proved. scurve_step_terms() is also what the conformance test
// (properties/xy/scurve/proof_test.cpp, suite ScurveProof) evaluates against the core's step()
// on concrete states. P6 is left out (the position is checked exactly by the tests).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/xy/scurve/profile.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

namespace sc = ap::xy_scurve;
constexpr unsigned kSegBits = 3;

// step(): state {seg (3 bits), tick, a, v2} and len[7] (all of one width W) -> the next state.
// Mirrors core/xy/scurve/src/profile.cpp step() with stopping = false:
//   finished (seg >= 7): unchanged; else j = kPlanJerk[seg]; A += j; V2 += 2A + j (old A);
//   tick + 1 >= len[seg]: next non-empty segment (7 if none), tick 0.
std::vector<z3::expr> scurve_step_terms(z3::context& c, const std::vector<z3::expr>& s, const std::vector<z3::expr>& len) {
  const z3::expr& seg = s[0];
  const z3::expr& tick = s[1];
  const z3::expr& a = s[2];
  const z3::expr& v2 = s[3];
  const unsigned w = tick.get_sort().bv_size();
  const auto sv = [&](unsigned i) { return c.bv_val(i, kSegBits); };
  z3::expr jerk = c.bv_val(0, w);
  z3::expr cur_len = c.bv_val(0, w);
  for (unsigned i = sc::kSegments; i-- > 0;) {
    jerk = z3::ite(seg == sv(i), c.bv_val(static_cast<int>(sc::kPlanJerk[i]), w), jerk);
    cur_len = z3::ite(seg == sv(i), len[i], cur_len);
  }
  // first non-empty segment at or after i (7 if none)
  std::vector<z3::expr> first_from;
  first_from.push_back(sv(sc::kSegments));
  for (unsigned i = sc::kSegments; i-- > 0;) {
    first_from.insert(first_from.begin(), z3::ite(len[i] != c.bv_val(0, w), sv(i), first_from.front()));
  }
  z3::expr next_seg = sv(sc::kSegments);
  for (unsigned i = sc::kSegments; i-- > 0;) next_seg = z3::ite(seg == sv(i), first_from[i + 1], next_seg);
  const z3::expr done = z3::uge(seg, sv(sc::kSegments));
  const z3::expr tick1 = tick + c.bv_val(1, w);
  const z3::expr wrap = z3::uge(tick1, cur_len);
  return {z3::ite(done, seg, z3::ite(wrap, next_seg, seg)), z3::ite(done, tick, z3::ite(wrap, c.bv_val(0, w), tick1)),
          z3::ite(done, a, a + jerk), z3::ite(done, v2, v2 + a + a + jerk)};
}

// start(): the first non-empty segment, tick 0, A = V2 = 0.
z3::expr scurve_start_seg(z3::context& c, const std::vector<z3::expr>& len) {
  const unsigned w = len[0].get_sort().bv_size();
  z3::expr f = c.bv_val(sc::kSegments, kSegBits);
  for (unsigned i = sc::kSegments; i-- > 0;) f = z3::ite(len[i] != c.bv_val(0, w), c.bv_val(i, kSegBits), f);
  return f;
}

namespace {

// A symbolic valid plan: Tj >= 1, Tc, Tv below 2^bits, lengths Tj, Tc, Tj, Tv, Tj, Tc, Tj.
struct SymPlan {
  z3::expr tj, tc, tv;
  std::vector<z3::expr> len;
  z3::expr valid;
  SymPlan(z3::context& c, unsigned w, unsigned bits)
      : tj(c.bv_const("Tj", w)), tc(c.bv_const("Tc", w)), tv(c.bv_const("Tv", w)),
        len{tj, tc, tj, tv, tj, tc, tj},
        valid(z3::uge(tj, c.bv_val(1, w)) && z3::ult(tj, c.bv_val(uint64_t{1} << bits, w)) &&
              z3::ult(tc, c.bv_val(uint64_t{1} << bits, w)) && z3::ult(tv, c.bv_val(uint64_t{1} << bits, w))) {}
};

// The acceleration the planned profile has at (seg, tick): tick, Tj, Tj - tick, 0, -tick, -Tj,
// -Tj + tick, 0 (seed-003.md §5.4's jerk pattern integrated).
z3::expr accel_at(z3::context& c, const SymPlan& p, const z3::expr& seg, const z3::expr& t) {
  const unsigned w = t.get_sort().bv_size();
  const std::array<z3::expr, 8> v{t, p.tj, p.tj - t, c.bv_val(0, w), -t, -p.tj, t - p.tj, c.bv_val(0, w)};
  z3::expr r = v[7];
  for (unsigned i = 7; i-- > 0;) r = z3::ite(seg == c.bv_val(i, kSegBits), v[i], r);
  return r;
}

// V2 of the planned profile at (seg, tick), with W = 2 Tj (Tj + Tc) the peak:
// t^2, Tj^2 + 2 Tj t, Tj^2 + 2 Tj Tc + 2 Tj t - t^2, W, W - t^2, Tj^2 - 2 Tj t + 2 Tj Tc ... (seg 5),
// (Tj - t)^2, 0.
z3::expr v2_at(z3::context& c, const SymPlan& p, const z3::expr& seg, const z3::expr& t) {
  const unsigned w = t.get_sort().bv_size();
  const z3::expr two = c.bv_val(2, w);
  const z3::expr tj2 = p.tj * p.tj;
  const z3::expr peak = two * tj2 + two * p.tj * p.tc;
  const std::array<z3::expr, 8> v{t * t,
                                  tj2 + two * p.tj * t,
                                  tj2 + two * p.tj * p.tc + two * p.tj * t - t * t,
                                  peak,
                                  peak - t * t,
                                  tj2 + two * p.tj * (p.tc - t),
                                  (p.tj - t) * (p.tj - t),
                                  c.bv_val(0, w)};
  z3::expr r = v[7];
  for (unsigned i = 7; i-- > 0;) r = z3::ite(seg == c.bv_val(i, kSegBits), v[i], r);
  return r;
}

z3::expr len_at(z3::context& c, const SymPlan& p, const z3::expr& seg) {
  z3::expr r = c.bv_val(0, p.tj.get_sort().bv_size());
  for (unsigned i = sc::kSegments; i-- > 0;) r = z3::ite(seg == c.bv_val(i, kSegBits), p.len[i], r);
  return r;
}

// Where the state may be: a segment 0..7 and, before the end, a tick inside a non-empty segment.
z3::expr position_ok(z3::context& c, const SymPlan& p, const z3::expr& seg, const z3::expr& t) {
  const z3::expr running = z3::ult(seg, c.bv_val(sc::kSegments, kSegBits));
  return z3::ule(seg, c.bv_val(sc::kSegments, kSegBits)) &&
         z3::implies(running, z3::ult(t, len_at(c, p, seg))) &&
         z3::implies(!running, t == c.bv_val(0, t.get_sort().bv_size()));
}

Obligation induction(const std::string& name, const std::string& method, unsigned w, unsigned bits, bool with_v,
                     int only_seg) {
  return {name, method, [=](unsigned ms) {
            z3::context& c = shared_context();
            const SymPlan p(c, w, bits);
            const z3::expr seg = c.bv_const("seg", kSegBits);
            const z3::expr t = c.bv_const("tick", w);
            const z3::expr a = c.bv_const("A", w);
            const z3::expr v2 = c.bv_const("V2", w);
            const auto inv = [&](const z3::expr& sg, const z3::expr& tk, const z3::expr& aa, const z3::expr& vv) {
              z3::expr r = position_ok(c, p, sg, tk) && aa == accel_at(c, p, sg, tk);
              if (with_v) r = r && vv == v2_at(c, p, sg, tk);
              return r;
            };
            const auto n = scurve_step_terms(c, {seg, t, a, v2}, p.len);
            const z3::expr zero = c.bv_val(0, w);
            z3::expr post = inv(n[0], n[1], n[2], n[3]) && z3::sle(-p.tj, n[2]) && z3::sle(n[2], p.tj);
            if (with_v) post = post && z3::sge(n[3], zero);
            z3::expr pre = p.valid && inv(seg, t, a, v2);
            if (only_seg >= 0) pre = pre && seg == c.bv_val(static_cast<unsigned>(only_seg), kSegBits);
            // Base case: start() satisfies the invariant (checked with the first segment).
            const z3::expr base = z3::implies(p.valid, inv(scurve_start_seg(c, p.len), zero, zero, zero));
            const z3::expr claim = base && z3::implies(pre, post);
            return check_valid(c, claim, ms,
                               {{"Tj", p.tj}, {"Tc", p.tc}, {"Tv", p.tv}, {"seg", seg}, {"tick", t}, {"A", a}, {"V2", v2},
                                {"seg'", n[0]}, {"tick'", n[1]}, {"A'", n[2]}, {"V2'", n[3]}});
          }};
}

}  // namespace

void add_scurve_obligations(ObligationList& out) {
  out.push_back({"scurve.step.jerk_bounded",
                 "QF_BV 64-bit, for every state (any segment, tick, A, V2) and any segment lengths: one step() "
                 "changes A by -1, 0 or +1, i.e. the jerk of a tick is in {-u, 0, +u} with u <= J (docs/scurve.md)",
                 [](unsigned ms) {
                   z3::context& c = shared_context();
                   constexpr unsigned w = 64;
                   const z3::expr seg = c.bv_const("seg", kSegBits);
                   const z3::expr t = c.bv_const("tick", w);
                   const z3::expr a = c.bv_const("A", w);
                   const z3::expr v2 = c.bv_const("V2", w);
                   std::vector<z3::expr> len;
                   for (unsigned i = 0; i < sc::kSegments; ++i) len.push_back(c.bv_const(("len" + std::to_string(i)).c_str(), w));
                   const auto n = scurve_step_terms(c, {seg, t, a, v2}, len);
                   const z3::expr d = n[2] - a;
                   const z3::expr claim = d == c.bv_val(0, w) || d == c.bv_val(1, w) || d == c.bv_val(-1, w);
                   return check_valid(c, claim, ms, {{"seg", seg}, {"A", a}, {"A'", n[2]}});
                 }});
  out.push_back(induction("scurve.step.accel_bounded",
                          "QF_BV 40-bit, by induction over ticks, for every plan with 1 <= Tj and Tj, Tc, Tv < 2^32: "
                          "start() has A = 0, and from any state where A is the planned acceleration of its segment and "
                          "tick (tick, Tj, Tj - tick, 0, -tick, -Tj, tick - Tj, 0) step() keeps that and |A| <= Tj "
                          "(so |a| <= Tj u <= a_max)",
                          40, 32, false, -1));
  for (int s = 0; s < 8; ++s) {
    out.push_back(induction("scurve.step.velocity_nonneg.seg" + std::to_string(s),
                            "QF_BV 16-bit, by induction over ticks, for every plan with 1 <= Tj and Tj, Tc, Tv < 2^6, "
                            "from every state in segment " + std::to_string(s) +
                                " whose A and V2 are the planned ones (V2 = t^2, Tj^2 + 2 Tj t, ..., (Tj - t)^2, 0): "
                                "step() keeps them, |A| <= Tj and V2 >= 0 (v >= 0); larger plans by property tests",
                            16, 6, true, s));
  }
}

}  // namespace ap::model::smt
