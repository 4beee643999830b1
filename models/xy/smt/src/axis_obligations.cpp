// Axis obligations (docs/proofs.md). Each states its claim, its method and its assumptions; the
// same text is in docs/proofs.md. Step-level claims use the encoding with Kernels::Contract
// (kernel results constrained only by the lemmas axis.dd.* / axis.best_fit.contract, which
// are proved about the exact kernels in QF_NIA, and whose side conditions
// axis.overflow.kernels proves, so the Int and bit-precise kernels agree).
// One file, longer than the others: it is one table, the list of the axis obligations in the
// order docs/proofs.md gives them, each entry a claim with its method and assumptions; splitting
// it would split the list the document mirrors.
#include "models/xy/smt/axis_obligations.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <utility>

#include "core/xy/axis/watchdog.hpp"
#include "models/xy/smt/axis_encoding.hpp"
#include "models/xy/smt/axis_kernels.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

namespace ax = ap::xy_axis;
using xy_axis::Encoder;
using xy_axis::Kernels;
using xy_axis::Sem;
using xy_axis::SymConfig;
using xy_axis::SymInput;
using xy_axis::SymOutput;
using xy_axis::SymState;

// ---- case files and traces -------------------------------------------------------------


std::string format_trace(const ax::Config& c, const std::vector<ax::State>& st, const std::vector<ax::Input>& in,
                         const std::vector<ax::Output>& out) {
  std::ostringstream o;
  o << "    config v_start=" << c.v_start << " v_slow=" << c.v_slow << " v_fast=" << c.v_fast << " accel=" << c.accel
    << " soft=[" << c.soft_min << "," << c.soft_max << "] home_travel=" << c.home_travel
    << " home_position=" << c.home_position << "\n";
  for (std::size_t i = 0; i < st.size(); ++i) {
    const auto& s = st[i];
    o << "    tick " << i << ": state phase=" << ax::phase_name(s.phase) << " mode=" << ax::mode_name(s.mode)
      << " dir=" << int(s.dir) << " pos=" << s.pos << " target=" << s.target << " speed=" << s.v
      << " (fine, 1/1000 ustep/s) frac=" << s.frac << " homed=" << int(s.homed) << " latch=" << int(s.latch_min)
      << "/" << int(s.latch_max) << "\n";
    if (i < in.size()) {
      const auto& x = in[i];
      o << "            input cmd=" << int(x.cmd.kind) << " dir=" << int(x.cmd.dir) << " level=" << int(x.cmd.level)
        << " value=" << x.cmd.value << " endstops=" << int(x.endstop_min) << "/" << int(x.endstop_max)
        << " blocked=" << int(x.blocked) << " link=" << int(x.link_alive);
      if (i < out.size()) {
        const auto& y = out[i];
        o << "  ->  edge " << ax::edge_letter(y.edge) << " class=" << int(y.cls) << " steps=" << y.steps
          << " dir=" << int(y.dir) << " step_speed=" << y.step_speed << " error=" << int(y.error);
      }
      o << "\n";
    }
  }
  return o.str();
}

namespace {

constexpr std::int64_t kDist = ax::kDistScale;

z3::expr w(const z3::expr& e) { return z3::sext(e, 64 - e.get_sort().bv_size()); }
z3::expr b8(z3::context& c, int v) { return c.bv_val(v, 8); }
z3::expr b64(z3::context& c, std::int64_t v) { return c.bv_val(v, 64); }

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// hyps -> goal, with a custom counterexample renderer. logic: "QF_BV", "QF_NIA" or nullptr.
Outcome decide(z3::context& c, const z3::expr& hyps, const z3::expr& goal, unsigned timeout_ms, const char* logic,
               const std::function<std::string(const z3::model&)>& on_sat) {
  const auto t0 = std::chrono::steady_clock::now();
  Outcome out;
  z3::solver s = logic != nullptr ? z3::solver(c, logic) : z3::solver(c);
  if (timeout_ms > 0) s.set("timeout", timeout_ms);
  s.add(hyps);
  s.add(!goal);
  const z3::check_result r = s.check();
  // A proof from unsatisfiable hypotheses says nothing (e.g. an invariant no state meets, or
  // contracts that contradict the encoding): the hypotheses alone must have a model.
  z3::check_result vac = z3::sat;
  if (r == z3::unsat) {
    z3::solver h = logic != nullptr ? z3::solver(c, logic) : z3::solver(c);
    if (timeout_ms > 0) h.set("timeout", timeout_ms);
    h.add(hyps);
    vac = h.check();
  }
  out.seconds = since(t0);
  if (r == z3::unsat && vac == z3::unsat) {
    out.verdict = Verdict::Failed;
    out.counterexample = "vacuous: the hypotheses have no model, so the proof would say nothing";
  } else if (r == z3::unsat && vac == z3::unknown) {
    out.verdict = Verdict::Unknown;
    out.counterexample = "proved, but the hypotheses' satisfiability is unknown: " + s.reason_unknown();
  } else if (r == z3::unsat) {
    out.verdict = Verdict::Proved;
  } else if (r == z3::sat) {
    out.verdict = Verdict::Failed;
    out.counterexample = on_sat(s.get_model());
  } else {
    out.verdict = Verdict::Unknown;
    out.counterexample = s.reason_unknown();
  }
  return out;
}

// ---- one-step (inductive-invariant) problems over the step encoding --------------------

struct StepProblem {
  z3::context& c;
  Encoder enc;
  SymConfig cfg;
  SymState s0;
  SymInput in;
  Encoder::Result r;
  StepProblem(z3::context& ctx, Kernels k, Sem sem = Sem::Bv)
      : c(ctx), enc(ctx, k, sem), cfg(enc.config(sem == Sem::Int ? "_i" : "")),
        s0(enc.state(sem == Sem::Int ? "_0i" : "_0")), in(enc.input(sem == Sem::Int ? "_0i" : "_0")),
        r(enc.step(s0, in, cfg)) {}

  // The code's own term: the int32 product v_start * kSpeedScale, widened (same hash-consed
  // term as in the encoding, so the solver need not relate a 32- and a 64-bit product).
  z3::expr s_fine() const { return enc.W(cfg.v_start * enc.L32(ax::kSpeedScale)); }
  // Valid config and state; in Int also every field (state, input, config) within its C++ type.
  z3::expr valid() {
    return enc.domain(cfg) && enc.domain(s0) && enc.domain(in) && enc.config_valid(cfg) && enc.state_valid(s0);
  }

  // Trace + replay case from a model: tick 0 from the model, then `run` more ticks of step().
  std::string render(const std::string& name, const z3::model& m, int run) const {
    const ax::Config kc = xy_axis::eval_config(m, cfg);
    const ax::State a = xy_axis::eval_state(m, s0);
    const ax::Input i0 = xy_axis::eval_input(m, in);
    const ax::State b = xy_axis::eval_state(m, r.state);
    const ax::Output o = xy_axis::eval_output(m, r.out);
    ReplayCase k;
    k.obligation = name;
    k.config = kc;
    k.state = a;
    k.inputs = {i0};
    k.run = run;
    const std::string path = write_case(k);
    return "tick-by-tick trace (from the model of the encoding):\n" + format_trace(kc, {a, b}, {i0}, {o}) +
           "    replay case written to " + path;
  }
};

using Builder = std::function<Outcome(unsigned)>;

void add(ObligationList& out, const std::string& name, const std::string& method, Builder b) {
  out.push_back({name, method, std::move(b)});
}

z3::expr is_mode(z3::context& c, const z3::expr& m, ax::Mode x) { return m == b8(c, static_cast<int>(x)); }
z3::expr is_phase(z3::context& c, const z3::expr& p, ax::Phase x) { return p == b8(c, static_cast<int>(x)); }
z3::expr is_kind(z3::context& c, const z3::expr& k, ax::CmdKind x) { return k == b8(c, static_cast<int>(x)); }
// The same over the encoder's semantics (Int twin).
z3::expr is_mode(const Encoder& e, const z3::expr& m, ax::Mode x) { return m == e.L8(static_cast<int>(x)); }
z3::expr is_phase(const Encoder& e, const z3::expr& p, ax::Phase x) { return p == e.L8(static_cast<int>(x)); }
z3::expr is_kind(const Encoder& e, const z3::expr& k, ax::CmdKind x) { return k == e.L8(static_cast<int>(x)); }


// ---- NIA lemma problems over the kernels ------------------------------------------------

struct KernelVars {
  z3::context& c;
  z3::expr v, s_us, s, a;
  explicit KernelVars(z3::context& ctx)
      : c(ctx), v(ctx.int_const("v")), s_us(ctx.int_const("v_start")), s(s_us * 1000), a(ctx.int_const("accel")) {}
  z3::expr pre() const {
    return v >= 0 && v <= ax::kFineSpeedMax && s_us >= 1 && s_us <= ax::kSpeedMax && a >= 1 && a <= ax::kAccelMax;
  }
  xy_axis::Arith ar(xy_axis::Checks* ch) const { return xy_axis::Arith(c, xy_axis::Sem::Int, ch, c.bool_val(true)); }
  z3::expr dd(const z3::expr& x) const { return xy_axis::stop_distance_fine(ar(nullptr), x, s, a); }
};

// A lemma counterexample (v, v_start, accel) as a motion scenario: a Position move at fine
// speed v toward a target the reference stopping distance says is reachable.
std::string kernel_case(const std::string& name, const z3::model& m, const KernelVars& k) {
  const auto v = static_cast<std::int32_t>(m.eval(k.v, true).get_numeral_int64());
  const auto s_us = static_cast<std::int32_t>(m.eval(k.s_us, true).get_numeral_int64());
  const auto a = static_cast<std::int32_t>(m.eval(k.a, true).get_numeral_int64());
  ReplayCase rc;
  rc.obligation = name;
  rc.config.v_start = s_us;
  rc.config.v_slow = s_us;
  const std::int32_t vu = (v + ax::kSpeedScale - 1) / ax::kSpeedScale;
  rc.config.v_fast = vu > s_us ? vu : s_us;
  rc.config.accel = a;
  rc.config.soft_min = -ax::kPosMax;
  rc.config.soft_max = ax::kPosMax;
  rc.state.phase = v > 0 ? ax::Phase::Const : ax::Phase::Stop;
  rc.state.mode = ax::Mode::Position;
  rc.state.level = 1;
  rc.state.homed = 1;
  rc.state.dir = 1;
  rc.state.pos = -ax::kPosMax / 2;
  rc.state.v = v;
  // A target beyond the true stopping distance plus one tick (sum computed independently, in
  // 128 bits so this oracle cannot share an overflow with the code it checks).
  __extension__ using wide = std::int64_t;
  const wide s = static_cast<wide>(s_us) * 1000;
  const wide mm = v > s ? (v - s + a - 1) / a - 1 : 0;
  const wide dd = mm * v - static_cast<wide>(a) * mm * (mm + 1) / 2;
  const wide need = (dd + v) / kDist + 2;
  rc.state.target = static_cast<std::int32_t>(rc.state.pos + (need < ax::kPosMax ? need : ax::kPosMax));
  rc.run = 200000;
  std::ostringstream o;
  o << "v=" << v << " v_start=" << s_us << " (s_fine=" << s_us * 1000 << ") accel=" << a
    << "\n    as a motion scenario: Position move at speed " << v << " toward target " << rc.state.target
    << " from " << rc.state.pos << "\n    replay case written to " << write_case(rc);
  return o.str();
}

// (goal - pos) * dir in steps, dir in {-1, 1} (state_valid): a select, linear in the Int twin.
z3::expr steps_ahead(const Encoder& e, const SymState& s, const z3::expr& goal64) {
  return z3::ite(s.dir == 1, goal64 - e.W(s.pos), e.W(s.pos) - goal64);
}
// ((goal - pos) * dir) * kDist - frac: the fine distance to the goal in the direction of motion.
z3::expr fine_room(const Encoder& e, const SymState& s, const z3::expr& goal64) {
  return steps_ahead(e, s, goal64) * e.L64(kDist) - e.W(s.frac);
}

// Step-level claims written once over the encoder's semantics. They are proved on the Int
// twin with the kernel contracts (QF_UFLIA: fast). When that fails, the same claim is asked of
// the exact bit-precise encoding (exact kernels, QF_BV): a model there is a counterexample of
// the code itself, so the case written for replay fails on the buggy build too; a contract
// model alone may be spurious (a best_fit or DD value the real kernel never returns), and the
// report says so.
using StepClaim = std::function<std::pair<z3::expr, z3::expr>(StepProblem&)>;  // (hypotheses, goal)

// The exact kernels at concrete arguments: the Int instantiation of axis_kernels.hpp on
// literals folds to a numeral (the same value as the C++ kernel: axis.overflow.kernels).
std::int64_t exact_dd(z3::context& c, std::int64_t v, std::int64_t s, std::int64_t a) {
  const xy_axis::Arith ar(c, Sem::Int, nullptr, c.bool_val(true));
  return xy_axis::ground_value(xy_axis::stop_distance_fine(ar, c.int_val(v), c.int_val(s), c.int_val(a)));
}
std::int64_t exact_best_fit(z3::context& c, std::int64_t lo, std::int64_t hi, std::int64_t room, std::int64_t s,
                            std::int64_t a) {
  const xy_axis::Arith ar(c, Sem::Int, nullptr, c.bool_val(true));
  return xy_axis::ground_value(
      xy_axis::best_fit(ar, c.int_val(lo), c.int_val(hi), c.int_val(room), c.int_val(s), c.int_val(a)));
}
bool in(std::int64_t x, std::int64_t lo, std::int64_t hi) { return x >= lo && x <= hi; }

// Counterexample-guided refinement of the kernel contracts: where the model gives DD or
// best_fit a value the exact kernel does not, pin the exact value at those arguments and ask
// again. A model that survives agrees with the real kernels at every call, so it is a
// counterexample of the code (the replay of the written case checks that on step()).
// Returns the number of facts added (0: the model is exact).
int refine(z3::context& c, z3::solver& s, const z3::model& m, const Encoder& enc) {
  auto val = [&](const z3::expr& e) { return m.eval(e, true).get_numeral_int64(); };
  int added = 0;
  for (const auto& d : enc.dd_apps) {
    const std::int64_t v = val(d.v), sf = val(d.s), a = val(d.a);
    // Only where the lemmas' preconditions hold (elsewhere the contract leaves DD free, and
    // the code never evaluates it).
    if (!in(v, sf + 1, ax::kFineSpeedMax) || !in(sf, 1000, ax::kFineSpeedMax) || sf % 1000 != 0 ||
        !in(a, 1, ax::kAccelMax)) {
      continue;
    }
    const std::int64_t want = exact_dd(c, v, sf, a);
    const z3::expr app = enc.dd_fun(c.int_val(v), c.int_val(sf), c.int_val(a));
    if (val(app) != want) {
      s.add(app == c.int_val(want));
      ++added;
    }
  }
  for (const auto& b : enc.bf_calls) {
    const std::int64_t lo = val(b.lo), hi = val(b.hi), room = val(b.room), sf = val(b.s), a = val(b.a);
    if (!in(lo, 1, hi) || !in(hi, lo, ax::kFineSpeedMax) || !in(room, 1, 3'000'000'000'000'000LL) ||
        !in(sf, 1000, ax::kFineSpeedMax) || !in(a, 1, ax::kAccelMax)) {
      continue;
    }
    const std::int64_t want = exact_best_fit(c, lo, hi, room, sf, a);
    if (val(b.bf) != want) {
      s.add(z3::implies(b.lo == c.int_val(lo) && b.hi == c.int_val(hi) && b.room == c.int_val(room) &&
                            b.s == c.int_val(sf) && b.a == c.int_val(a),
                        b.bf == c.int_val(want)));
      ++added;
    }
  }
  return added;
}

Outcome prove_step(const std::string& name, unsigned t, int run, const StepClaim& claim) {
  z3::context& c = shared_context();
  StepProblem p(c, Kernels::Contract, Sem::Int);
  const auto [hyp, goal] = claim(p);
  const z3::expr hyps = p.valid() && hyp && p.enc.all_contracts();
  Outcome o = decide(c, hyps, goal, t, nullptr, [&](const z3::model& m) { return p.render(name, m, run); });
  if (o.verdict != Verdict::Failed || o.counterexample.rfind("vacuous", 0) == 0) return o;
  // Failed on the contracts: look for a model that is exact at every kernel call.
  const auto t0 = std::chrono::steady_clock::now();
  z3::solver s(c);
  if (t > 0) s.set("timeout", t);
  s.add(hyps);
  s.add(!goal);
  constexpr int kRounds = 64;
  for (int round = 0; round < kRounds; ++round) {
    const z3::check_result r = s.check();
    if (r == z3::unsat) {
      // Every added fact is true of the exact kernels, so no counterexample exists for them.
      o.verdict = Verdict::Proved;
      o.seconds += since(t0);
      o.counterexample.clear();
      return o;
    }
    if (r != z3::sat) break;
    const z3::model m = s.get_model();
    if (refine(c, s, m, p.enc) == 0) {
      o.seconds += since(t0);
      o.counterexample = "counterexample (kernels exact at every call after " + std::to_string(round) +
                         " refinement rounds):\n    " + p.render(name, m, run);
      return o;
    }
  }
  o.seconds += since(t0);
  o.counterexample = "counterexample of the kernel contracts only (no model exact at every kernel call within " +
                     std::to_string(kRounds) + " refinement rounds; it may be spurious):\n    " + o.counterexample;
  return o;
}

// best_fit's contract (brakes_fully = false) and its full-braking clause (true), two queries.
Outcome best_fit_contract(unsigned t, bool brakes_fully) {
  z3::context& c = shared_context();
  const KernelVars k(c);
  const z3::expr lo = c.int_const("lo"), hi = c.int_const("hi"), room = c.int_const("room");
  std::vector<xy_axis::PieceTerms> pieces;
  const z3::expr r = xy_axis::best_fit(k.ar(nullptr), lo, hi, room, k.s, k.a, &pieces);
  const z3::func_decl D = c.function("DDint", c.int_sort(), c.int_sort());
  auto can = [&](const z3::expr& x) { return x <= k.s || x + D(x) < room; };
  z3::expr lemma = c.bool_val(true);
  for (const auto& p : pieces) {
    lemma = lemma && z3::implies(p.m >= 0 && p.m <= ax::kFineSpeedMax && p.num >= 0 && p.x <= p.q &&
                                     p.x >= p.p_lo && p.x <= p.p_hi,
                                 p.x + D(p.x) < room);
  }
  // axis.dd.monotone at (lo, x) for each piece's candidate x.
  for (const auto& p : pieces) {
    if (!brakes_fully) break;
    lemma = lemma && z3::implies(k.s < lo && lo <= p.x && p.x <= ax::kFineSpeedMax, lo + D(lo) <= p.x + D(p.x));
  }
  const z3::expr pre = k.pre() && lo >= 1 && lo <= hi && hi <= ax::kFineSpeedMax && room >= 1 &&
                       room <= c.int_val(std::int64_t{3'000'000'000'000'000});
  const z3::expr goal = brakes_fully ? z3::implies(!can(lo), r == lo)
                                     : lo <= r && r <= hi && z3::implies(can(lo), can(r));
  return decide(c, pre && lemma, goal, t, nullptr, [&](const z3::model& m) {
    return "lo=" + m.eval(lo, true).to_string() + " hi=" + m.eval(hi, true).to_string() +
           " room=" + m.eval(room, true).to_string() + " best_fit=" + m.eval(r, true).to_string() + " " +
           kernel_case(brakes_fully ? "axis.best_fit.brakes_fully" : "axis.best_fit.contract", m, k);
  });
}

}  // namespace

void add_axis_obligations(ObligationList& out) {
  // ---- kernel lemmas (QF_NIA over the exact kernels) ----------------------------------
  add(out, "axis.overflow.kernels",
      "QF_NIA: every intermediate of stop_distance_fine and best_fit in its C++ type's range "
      "(int32/int64), divisions with dividend >= 0 and divisor > 0, for all args in range",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        xy_axis::Checks ch;
        const auto ar = k.ar(&ch);
        (void)xy_axis::stop_distance_fine(ar, k.v, k.s, k.a);
        const z3::expr lo = c.int_const("lo"), hi = c.int_const("hi"), room = c.int_const("room");
        (void)xy_axis::best_fit(ar, lo, hi, room, k.s, k.a);
        const z3::expr pre = k.pre() && lo >= 1 && lo <= hi && hi <= ax::kFineSpeedMax && room >= 1 &&
                             room <= c.int_val(std::int64_t{3'000'000'000'000'000});
        z3::expr all = c.bool_val(true);
        for (const auto& x : ch) all = all && z3::implies(x.guard, x.cond);
        std::vector<std::pair<std::string, z3::expr>> shown;
        return decide(c, pre, all, t, nullptr, [&](const z3::model& m) {
          std::string s;
          for (const auto& x : ch) {
            if (m.eval(x.guard && !x.cond, true).is_true()) s += "violated: " + x.name + "\n    ";
          }
          s += "lo=" + m.eval(lo, true).to_string() + " hi=" + m.eval(hi, true).to_string() +
               " room=" + m.eval(room, true).to_string() + " ";
          return s + kernel_case("axis.overflow.kernels", m, k);
        });
      });
  add(out, "axis.dd.bound", "QF_NIA lemma: 0 <= DD(v) <= 1e18 for all v, v_start, accel in range",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        const z3::expr d = k.dd(k.v);
        return decide(c, k.pre(), d >= 0 && d <= c.int_val(std::int64_t{1'000'000'000'000'000'000}), t, nullptr,
                      [&](const z3::model& m) { return "DD=" + m.eval(d, true).to_string() + " " + kernel_case("axis.dd.bound", m, k); });
      });
  add(out, "axis.dd.zero", "QF_NIA lemma: v - accel <= s_fine -> DD(v) = 0 (last braking tick is at start speed)",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        const z3::expr d = k.dd(k.v);
        return decide(c, k.pre() && k.v - k.a <= k.s, d == 0, t, nullptr,
                      [&](const z3::model& m) { return "DD=" + m.eval(d, true).to_string() + " " + kernel_case("axis.dd.zero", m, k); });
      });
  add(out, "axis.dd.quotient_shift",
      "QF_NIA lemma: x = v - s_fine - 1 >= accel -> (x - accel) / accel = x / accel - 1",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        const z3::expr x = k.v - k.s - 1;
        return decide(c, k.pre() && x >= k.a, (x - k.a) / k.a == x / k.a - 1, t, nullptr,
                      [&](const z3::model& m) { return kernel_case("axis.dd.quotient_shift", m, k); });
      });
  add(out, "axis.dd.recurrence",
      "QF_NIA lemma (uses axis.dd.quotient_shift): v - accel > s_fine -> DD(v) = (v - accel) + DD(v - accel)",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        const z3::expr d = k.dd(k.v);
        const z3::expr d2 = k.dd(k.v - k.a);
        const z3::expr x = k.v - k.s - 1;
        const z3::expr shift = (x - k.a) / k.a == x / k.a - 1;
        return decide(c, k.pre() && k.v - k.a > k.s && shift, d == (k.v - k.a) + d2, t, nullptr, [&](const z3::model& m) {
          return "DD(v)=" + m.eval(d, true).to_string() + " DD(v-a)=" + m.eval(d2, true).to_string() + " " +
                 kernel_case("axis.dd.recurrence", m, k);
        });
      });
  add(out, "axis.dd.monotone",
      "induction on v2 (steps of accel >= 1, well-founded above s_fine), step in QF_UFLIA with DD uninterpreted "
      "and constrained by axis.dd.bound/zero/recurrence: s_fine < v1 <= v2 -> v1 + DD(v1) <= v2 + DD(v2) (the "
      "distance to stop, this tick included, grows with the speed)",
      [](unsigned t) {
        z3::context& c = shared_context();
        const z3::expr s = c.int_const("s_fine"), a = c.int_const("accel");
        const z3::expr v1 = c.int_const("v1"), v2 = c.int_const("v2");
        const z3::func_decl D = c.function("DDmono", c.int_sort(), c.int_sort());
        auto f = [&](const z3::expr& x) { return x + D(x); };
        // The proved facts about DD at the four speeds involved.
        z3::expr facts = c.bool_val(true);
        for (const z3::expr& x : {v1, v2, v1 - a, v2 - a}) facts = facts && D(x) >= 0;
        for (const z3::expr& x : {v1, v2}) {
          facts = facts && z3::implies(x - a <= s, D(x) == 0) && z3::implies(x - a > s, D(x) == (x - a) + D(x - a));
        }
        const z3::expr ranges = s >= 1000 && s <= ax::kFineSpeedMax && a >= 1 && a <= ax::kAccelMax &&
                                v2 <= ax::kFineSpeedMax;
        // Induction hypothesis: the claim for the pair one braking tick lower (smaller v2).
        const z3::expr ih = z3::implies(s < v1 - a && v1 - a <= v2 - a, f(v1 - a) <= f(v2 - a));
        return decide(c, ranges && facts && ih && s < v1 && v1 <= v2, f(v1) <= f(v2), t, nullptr,
                      [&](const z3::model& m) {
                        return "v1=" + m.eval(v1, true).to_string() + " v2=" + m.eval(v2, true).to_string() +
                               " s_fine=" + m.eval(s, true).to_string() + " accel=" + m.eval(a, true).to_string();
                      });
      });
  add(out, "axis.best_fit.piece_quotient",
      "QF_NIA lemma: s_fine+1+m*a <= x <= s_fine+(m+1)*a -> (x - s_fine - 1) / a = m (x lies in piece m)",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        const z3::expr m = c.int_const("m");
        const z3::expr hyp = k.pre() && m >= 0 && m <= ax::kFineSpeedMax && k.v >= k.s + 1 + m * k.a &&
                             k.v <= k.s + (m + 1) * k.a;
        return decide(c, hyp, (k.v - k.s - 1) / k.a == m, t, nullptr,
                      [&](const z3::model& mm) { return kernel_case("axis.best_fit.piece_quotient", mm, k); });
      });
  add(out, "axis.best_fit.piece",
      "QF_NIA lemma (uses piece_quotient): a candidate x of piece m (p_lo <= x <= min(num/(m+1), p_hi)) "
      "satisfies x + DD(x) < room",
      [](unsigned t) {
        z3::context& c = shared_context();
        const KernelVars k(c);
        const z3::expr m = c.int_const("m"), room = c.int_const("room");
        const z3::expr x = k.v;
        const z3::expr p_lo = k.s + 1 + m * k.a, p_hi = k.s + (m + 1) * k.a;
        const z3::expr num = room - 1 + (k.a * m) * (m + 1) / 2;
        const z3::expr q = num / (m + 1);
        const z3::expr hyp = k.pre() && m >= 0 && m <= ax::kFineSpeedMax && room >= 1 &&
                             room <= c.int_val(std::int64_t{3'000'000'000'000'000}) && num >= 0 && x <= q &&
                             x >= p_lo && x <= p_hi && (x - k.s - 1) / k.a == m;
        return decide(c, hyp, x + k.dd(x) < room, t, nullptr,
                      [&](const z3::model& mm) { return "m=" + mm.eval(m, true).to_string() + " room=" + mm.eval(room, true).to_string() + " " + kernel_case("axis.best_fit.piece", mm, k); });
      });
  add(out, "axis.best_fit.contract",
      "QF_UFNIA (DD uninterpreted, constrained by axis.best_fit.piece at the three unrolled pieces): "
      "lo <= best_fit <= hi and can_stop(lo) -> can_stop(best_fit), for 1 <= lo <= hi <= 1e9, 1 <= room <= 3e15",
      [](unsigned t) { return best_fit_contract(t, false); });
  add(out, "axis.best_fit.brakes_fully",
      "QF_UFNIA (DD uninterpreted, constrained by axis.best_fit.piece at the three unrolled pieces and "
      "axis.dd.monotone): !can_stop(lo) -> best_fit = lo, i.e. when even full braking cannot stop in time the code "
      "brakes fully, for 1 <= lo <= hi <= 1e9, 1 <= room <= 3e15",
      [](unsigned t) { return best_fit_contract(t, true); });
  add(out, "axis.narrowing",
      "QF_BV, all bit patterns: x in [0, 2^31) -> x = zext(low 32 bits of x); for every uint32 y < 2^31 the "
      "int64 x/1e6 and x%1e6 of x = zext(y) equal the 32-bit unsigned ones; x * d for d = 1, -1, 0 equals "
      "x, -x, 0 (the proof encoding's rewrites, Kernels::Contract)",
      [](unsigned t) {
        z3::context& c = shared_context();
        const z3::expr x = c.bv_const("x", 64), y = c.bv_const("y", 32), q = c.bv_const("q", 32), r = c.bv_const("r", 32);
        const z3::expr k64 = b64(c, kDist), k32 = c.bv_val(static_cast<int>(kDist), 32);
        const z3::expr in31 = x >= b64(c, 0) && x <= b64(c, std::numeric_limits<std::int32_t>::max());
        const z3::expr zx = z3::zext(y, 32);
        const z3::expr y31 = z3::ult(y, c.bv_val(0x80000000U, 32));
        const z3::expr claim = z3::implies(in31, x == z3::zext(x.extract(31, 0), 32)) &&
                               z3::implies(y31, zx / k64 == z3::zext(z3::udiv(y, k32), 32) &&
                                                    z3::srem(zx, k64) == z3::zext(z3::urem(y, k32), 32)) &&
                               x * w(b8(c, 1)) == x && x * w(b8(c, -1)) == -x && x * w(b8(c, 0)) == b64(c, 0) &&
                               z3::bvmul_no_overflow(z3::zext(q, 32), k64, false) &&
                               z3::bvadd_no_overflow(z3::zext(q, 32) * k64, z3::zext(r, 32), false);
        return decide(c, c.bool_val(true), claim, t, "QF_BV", [&](const z3::model& m) {
          return "x=" + m.eval(x, true).to_string() + " y=" + m.eval(y, true).to_string();
        });
      });

  add(out, "axis.narrowing.division",
      "QF_LIA: for integers 0 <= y < 2^31 and 0 <= q, r < 2^32, y = q*1e6 + r & r < 1e6 -> q = y div 1e6 & "
      "r = y mod 1e6 (C++ / and % for y >= 0); with axis.narrowing (no wrap) the proof encoding's q, r are "
      "step()'s quotient and remainder",
      [](unsigned t) {
        z3::context& c = shared_context();
        const z3::expr y = c.int_const("y"), q = c.int_const("q"), r = c.int_const("r");
        const z3::expr k = c.int_val(static_cast<int>(kDist));
        const z3::expr hyp = y >= 0 && y <= std::numeric_limits<std::int32_t>::max() && q >= 0 &&
                             q <= c.int_val(std::int64_t{4294967295}) && r >= 0 && r < k && y == q * k + r;
        return decide(c, hyp, q == y / k && r == z3::mod(y, k), t, nullptr,
                      [&](const z3::model& m) { return "y=" + m.eval(y, true).to_string(); });
      });

  // ---- step-level (QF_BV over the bit-precise step encoding, kernel contracts) ----------
  add(out, "axis.overflow.step",
      "QF_BV: no-overflow predicate of every add/sub/mul/div/cast in step() outside the kernels, and the kernel "
      "preconditions at each call, for every config, state and input bit pattern",
      [](unsigned t) {
        StepProblem p(shared_context(), Kernels::Contract);
        return decide(p.c, p.enc.all_contracts(), p.enc.no_overflow(), t, "QF_BV", [&](const z3::model& m) {
          std::string s;
          for (const auto& x : p.enc.checks) {
            if (m.eval(x.guard && !x.cond, true).is_true()) s += "violated: " + x.name + "\n    ";
          }
          return s + p.render("axis.overflow.step", m, 0);
        });
      });
  add(out, "axis.state_valid.inductive",
      "QF_BV inductive invariant (1-induction): config_valid & state_valid(s) -> state_valid(step(s, in))",
      [](unsigned t) {
        StepProblem p(shared_context(), Kernels::Contract);
        return decide(p.c, p.valid() && p.enc.all_contracts(), p.enc.state_valid(p.r.state), t, "QF_BV",
                      [&](const z3::model& m) { return p.render("axis.state_valid.inductive", m, 0); });
      });
  add(out, "axis.table.total_deterministic",
      "QF_BV exhaustive over all phase x class codes: exactly one of the 15 edge guards holds and edge_for "
      "returns it; step() emits that edge for every valid state and input",
      [](unsigned t) {
        z3::context& c = shared_context();
        const z3::expr ph = c.bv_const("phase", 8), cl = c.bv_const("cls", 8);
        const z3::expr e = xy_axis::sym_edge_for(c, ph, cl);
        z3::expr one = c.bool_val(true);
        for (int i = 0; i < ax::kEdgeCount; ++i) {
          const z3::expr gi = xy_axis::sym_edge_guard(c, i, ph, cl);
          one = one && (gi == (e == b8(c, i)));
        }
        StepProblem p(c, Kernels::Contract);
        const z3::expr step_ok = z3::implies(p.valid() && p.enc.all_contracts(),
                                             z3::ule(p.r.out.cls, 6) &&
                                                 p.r.out.edge == xy_axis::sym_edge_for(c, p.s0.phase, p.r.out.cls));
        return decide(c, c.bool_val(true), z3::implies(z3::ule(ph, 3) && z3::ule(cl, 6), one) && step_ok, t, "QF_BV",
                      [&](const z3::model& m) {
                        ReplayCase rc;
                        rc.obligation = "axis.table.total_deterministic";
                        rc.kind = "table";
                        return "phase=" + m.eval(ph, true).to_string() + " class=" + m.eval(cl, true).to_string() +
                               " edge_for=" + m.eval(e, true).to_string() +
                               "\n    replay case (every phase x class through edge_for/edge_guard) written to " +
                               write_case(rc);
                      });
      });
  add(out, "axis.speed.max",
      "QF_UFLIA (Int twin of the step encoding) inductive invariant (1-induction), fixed config: "
      "v <= v_fast*1000 -> v' <= v_fast*1000 and step_speed <= v_fast*1000; base: v = 0 at rest",
      [](unsigned t) {
        return prove_step("axis.speed.max", t, 2000, [](StepProblem& p) {
          const Encoder& e = p.enc;
          const z3::expr vmax = e.W(p.cfg.v_fast * e.L32(ax::kSpeedScale));  // the code's product
          return std::pair{e.W(p.s0.v) <= vmax, e.W(p.r.state.v) <= vmax && e.W(p.r.out.step_speed) <= vmax};
        });
      });
  add(out, "axis.soft_limits",
      "QF_UFLIA (Int twin of the step encoding) inductive invariant (1-induction), fixed config, I: (mode=Home -> "
      "homed=0) & (mode=Position & homed -> soft_min <= target <= soft_max): while homed, no tick moves pos past "
      "soft_min/soft_max (pos' within [min(pos,soft_min), max(pos,soft_max)]); re-referencing by a Home command "
      "excluded",
      [](unsigned t) {
        return prove_step("axis.soft_limits", t, 2000, [](StepProblem& p) {
          const Encoder& e = p.enc;
          auto inv = [&](const SymState& s) {
            return z3::implies(is_mode(e, s.mode, ax::Mode::Home), s.homed == 0) &&
                   z3::implies(is_mode(e, s.mode, ax::Mode::Position) && s.homed == 1,
                               s.target >= p.cfg.soft_min && s.target <= p.cfg.soft_max);
          };
          const z3::expr hyp = inv(p.s0) && p.s0.homed == 1 && !is_kind(e, p.in.kind, ax::CmdKind::Home);
          const SymState& n = p.r.state;
          const z3::expr hi = z3::ite(p.s0.pos > p.cfg.soft_max, p.s0.pos, p.cfg.soft_max);
          const z3::expr lo = z3::ite(p.s0.pos < p.cfg.soft_min, p.s0.pos, p.cfg.soft_min);
          const z3::expr goal = inv(n) && z3::implies(n.homed == 1, n.pos <= hi && n.pos >= lo);
          const z3::expr base = z3::implies(p.s0.homed == 0 || !is_mode(e, p.s0.mode, ax::Mode::Home), inv(p.s0));
          return std::pair{hyp, goal && base};
        });
      });
  add(out, "axis.dir.reverse_at_start_speed",
      "QF_BV, every valid state and input: DIR changes only when v <= s_fine (at rest: edge A), and never in a "
      "tick that emits steps",
      [](unsigned t) {
        StepProblem p(shared_context(), Kernels::Contract);
        const z3::expr goal = z3::implies(p.r.state.dir != p.s0.dir, w(p.s0.v) <= p.s_fine() && p.r.out.steps == 0) &&
                              z3::implies(p.r.out.steps != 0, p.r.out.dir == p.s0.dir);
        return decide(p.c, p.valid() && p.enc.all_contracts(), goal, t, "QF_BV",
                      [&](const z3::model& m) { return p.render("axis.dir.reverse_at_start_speed", m, 2000); });
      });
  add(out, "axis.endstop.no_step_toward",
      "QF_BV, every valid state and input: steps > 0 toward max -> max endstop input and latch off (min alike)",
      [](unsigned t) {
        StepProblem p(shared_context(), Kernels::Contract);
        const z3::expr st = p.r.out.steps > 0;
        const z3::expr goal =
            z3::implies(st && p.r.out.dir > 0, p.in.endstop_max == 0 && p.s0.latch_max == 0) &&
            z3::implies(st && p.r.out.dir < 0, p.in.endstop_min == 0 && p.s0.latch_min == 0);
        return decide(p.c, p.valid() && p.enc.all_contracts(), goal, t, "QF_BV",
                      [&](const z3::model& m) { return p.render("axis.endstop.no_step_toward", m, 0); });
      });
  add(out, "axis.position.no_overshoot",
      "QF_UFLIA (Int twin of the step encoding) inductive invariant (1-induction) I: Position & moving -> "
      "dir*(target-pos) >= 1 & (v > s_fine -> DD(v) < room); fixed config; inputs: no command, or a move from "
      "rest, or a retarget at least the stopping distance ahead in the direction of motion; blocked = 0. Claim: "
      "pos never crosses the target; arrival step_speed <= s_fine",
      [](unsigned t) {
        return prove_step("axis.position.no_overshoot", t, 200000, [](StepProblem& p) {
          Encoder& e = p.enc;
          const z3::expr sf = p.s_fine();
          const z3::expr a = e.W(p.cfg.accel);
          auto inv = [&](const SymState& s) {
            const z3::expr pos_mode = is_mode(e, s.mode, ax::Mode::Position);
            const z3::expr moving = !is_phase(e, s.phase, ax::Phase::Stop);
            const z3::expr in_lim = s.homed == 0 || (s.target >= p.cfg.soft_min && s.target <= p.cfg.soft_max);
            const z3::expr dd = e.dd(e.W(s.v), sf, a, p.c.bool_val(false));
            return z3::implies(pos_mode, in_lim) &&
                   z3::implies(pos_mode && moving, steps_ahead(e, s, e.W(s.target)) >= e.L64(1) &&
                                                       z3::implies(e.W(s.v) > sf, dd < fine_room(e, s, e.W(s.target))));
          };
          const SymState& s = p.s0;
          const SymInput& in = p.in;
          const z3::expr t64 = z3::ite(is_kind(e, in.kind, ax::CmdKind::MoveAbs), e.W(in.value), e.W(s.pos) + e.W(in.value));
          const z3::expr d_new = z3::ite(t64 > e.W(s.pos), e.L8(1), z3::ite(t64 < e.W(s.pos), e.L8(-1), e.L8(0)));
          const z3::expr dd_now = e.dd(e.W(s.v), sf, a, p.c.bool_val(false));
          const z3::expr reachable = is_phase(e, s.phase, ax::Phase::Stop) ||
                                     (d_new == s.dir && (e.W(s.v) <= sf || dd_now < fine_room(e, s, t64)));
          const z3::expr move = is_kind(e, in.kind, ax::CmdKind::MoveAbs) || is_kind(e, in.kind, ax::CmdKind::MoveRel);
          const z3::expr inputs = in.blocked == 0 && (is_kind(e, in.kind, ax::CmdKind::None) || (move && reachable));
          const SymState& n = p.r.state;
          const z3::expr tt = e.W(n.target);
          const z3::expr was_pos = is_mode(e, n.mode, ax::Mode::Position) ||
                                   (is_mode(e, s.mode, ax::Mode::Position) && is_kind(e, in.kind, ax::CmdKind::None));
          // (t - pos') * (t - pos) >= 0, i.e. both on the same side (or on the target): never crosses.
          const z3::expr x = tt - e.W(n.pos), y = tt - e.W(s.pos);
          const z3::expr zero = e.L64(0);
          const z3::expr no_cross = (x >= zero && y >= zero) || (x <= zero && y <= zero);
          const z3::expr arrive = z3::implies(n.pos == n.target && s.pos != n.target, e.W(p.r.out.step_speed) <= sf);
          const z3::expr goal = inv(n) && z3::implies(was_pos, no_cross && arrive);
          // Base case: the initial state (initial_state(): at rest, idle) satisfies I.
          const z3::expr base =
              z3::implies(is_phase(e, s.phase, ax::Phase::Stop) && is_mode(e, s.mode, ax::Mode::Idle), inv(s));
          return std::pair{inv(s) && inputs, goal && base};
        });
      });
  add(out, "axis.position.overrun",
      "QF_UFLIA (Int twin of the step encoding) inductive invariant (1-induction until the carriage stops) with ghosts "
      "T (fine travel since the retarget) and Phi(v) = v > s_fine ? DD(v) + s_fine : 0. U: Position & moving & "
      "(target ahead -> v > s_fine & DD(v) >= room), i.e. the target is behind, at the carriage, or closer than the "
      "stopping distance. Claim: U & T + Phi(v) <= Phi0 is kept until the stop, so the carriage brakes at full "
      "deceleration and travels at most DD(v_r) + s_fine past the retarget point before it stops (and then starts "
      "back from rest: axis.position.no_overshoot); fixed config, no command, blocked = 0, endstops and link any",
      [](unsigned t) {
        return prove_step("axis.position.overrun", t, 200000, [](StepProblem& p) {
          Encoder& e = p.enc;
          const z3::expr sf = p.s_fine();
          const z3::expr a = e.W(p.cfg.accel);
          auto dd = [&](const SymState& s) { return e.dd(e.W(s.v), sf, a, p.c.bool_val(false)); };
          auto phi = [&](const SymState& s) { return z3::ite(e.W(s.v) > sf, dd(s) + sf, e.L64(0)); };
          auto unreachable = [&](const SymState& s) {
            const z3::expr ahead = steps_ahead(e, s, e.W(s.target)) >= e.L64(1);
            return is_mode(e, s.mode, ax::Mode::Position) && !is_phase(e, s.phase, ax::Phase::Stop) &&
                   z3::implies(ahead, e.W(s.v) > sf && dd(s) >= fine_room(e, s, e.W(s.target)));
          };
          const z3::expr T = e.var("T", 64), phi0 = e.var("Phi0", 64);
          auto inv = [&](const SymState& s, const z3::expr& tt) {
            return unreachable(s) && tt >= e.L64(0) && tt <= phi0 && tt + phi(s) <= phi0;
          };
          const z3::expr hyp = is_kind(e, p.in.kind, ax::CmdKind::None) && p.in.blocked == 0 && phi0 >= e.L64(0) &&
                               phi0 <= e.L64(2'000'000'000'000'000'000LL) && inv(p.s0, T);
          const SymState& n = p.r.state;
          const z3::expr T2 = T + e.W(p.r.out.step_speed);
          const z3::expr goal = (is_phase(e, n.phase, ax::Phase::Stop) && T2 <= phi0) || inv(n, T2);
          return std::pair{hyp, goal};
        });
      });
  add(out, "axis.watchdog.timeout",
      "QF_BV 1-induction over watchdog_tick (uint16) with a ghost tick count n: silent = min(n, 300), so the "
      "link is reported lost exactly 300 ticks (3 command periods) after the last valid frame",
      [](unsigned t) {
        z3::context& c = shared_context();
        const z3::expr silent = c.bv_const("silent", 16), n = c.bv_const("n", 16), valid = c.bool_const("valid");
        const z3::expr lim = c.bv_val(ax::kLinkTimeoutTicks, 16);
        auto inv = [&](const z3::expr& sl, const z3::expr& nn) {
          return z3::ule(nn, c.bv_val(1000, 16)) && sl == z3::ite(z3::ult(nn, lim), nn, lim);
        };
        const z3::expr s2 = xy_axis::sym_watchdog_tick(c, silent, valid);
        const z3::expr n2 = z3::ite(valid, c.bv_val(0, 16), z3::ite(z3::ult(n, c.bv_val(1000, 16)), n + 1, n));
        const z3::expr claim = inv(s2, n2) && (xy_axis::sym_link_alive(c, s2) == z3::ult(n2, lim));
        const z3::expr base = inv(lim, lim);  // LinkWatchdog{} starts expired: as if 300 ticks silent
        return decide(c, inv(silent, n), claim && base, t, "QF_BV", [&](const z3::model& m) {
          ReplayCase rc;
          rc.obligation = "axis.watchdog.timeout";
          rc.kind = "watchdog";
          return "silent=" + m.eval(silent, true).to_string() + " n=" + m.eval(n, true).to_string() +
                 " valid=" + m.eval(valid, true).to_string() +
                 "\n    replay case (1000 silent ticks after a frame through watchdog_tick) written to " + write_case(rc);
        });
      });
  add(out, "axis.watchdog.stop_begins",
      "QF_BV, every valid state: link lost (link_alive = 0, no frame) while jogging -> mode Idle in the same "
      "tick and the speed drops (v' < v) or the axis is stopped",
      [](unsigned t) {
        StepProblem p(shared_context(), Kernels::Contract);
        z3::context& c = p.c;
        const z3::expr hyp = p.valid() && p.enc.all_contracts() && is_mode(c, p.s0.mode, ax::Mode::Jog) &&
                             p.in.link_alive == 0 && is_kind(c, p.in.kind, ax::CmdKind::None);
        const z3::expr goal = is_mode(c, p.r.state.mode, ax::Mode::Idle) &&
                              (is_phase(c, p.r.state.phase, ax::Phase::Stop) || p.r.state.v < p.s0.v);
        return decide(c, hyp, goal, t, "QF_BV", [&](const z3::model& m) { return p.render("axis.watchdog.stop_begins", m, 2000); });
      });
  add(out, "axis.watchdog.stop_distance",
      "QF_UFLIA (Int twin of the step encoding) inductive invariant (1-induction) with ghost T (fine travel "
      "since the stop began) and Phi(v) = v > s_fine ? DD(v) + s_fine : 0: T + Phi(v) <= Phi(v0); so the stop "
      "completes within DD(v0) + one tick at start speed; inputs: no frame (no command), any endstop/blocked",
      [](unsigned t) {
        return prove_step("axis.watchdog.stop_distance", t, 200000, [](StepProblem& p) {
          Encoder& e = p.enc;
          const z3::expr sf = p.s_fine();
          const z3::expr a = e.W(p.cfg.accel);
          auto phi = [&](const SymState& s) {
            return z3::ite(e.W(s.v) > sf, e.dd(e.W(s.v), sf, a, p.c.bool_val(false)) + sf, e.L64(0));
          };
          // Ghosts (64-bit in the bit-precise encoding, where the bounds keep the sums from wrapping:
          // T <= Phi0 <= 2e18 and Phi <= 1e18 + 1e9).
          const z3::expr T = e.var("T", 64), phi0 = e.var("Phi0", 64);
          auto inv = [&](const SymState& s, const z3::expr& tt) {
            return is_mode(e, s.mode, ax::Mode::Idle) && tt >= e.L64(0) && tt <= phi0 && tt + phi(s) <= phi0;
          };
          const z3::expr hyp = is_kind(e, p.in.kind, ax::CmdKind::None) && phi0 >= e.L64(0) &&
                               phi0 <= e.L64(2'000'000'000'000'000'000LL) && inv(p.s0, T);
          const z3::expr T2 = T + e.W(p.r.out.step_speed);
          const z3::expr base =
              z3::implies(phi0 == phi(p.s0) && is_mode(e, p.s0.mode, ax::Mode::Idle), inv(p.s0, e.L64(0)));
          return std::pair{hyp, inv(p.r.state, T2) && base};
        });
      });
}

}  // namespace ap::model::smt
