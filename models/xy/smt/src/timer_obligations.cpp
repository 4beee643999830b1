// Step-timer obligations: step_timer() (core/xy/axis/include/core/xy/axis/step_timer.hpp) through
// the shared kernel text (axis_kernels.hpp), in QF_NIA over every requested frequency
// f in [1, kStepFreqMax]; no-wrap side conditions make the uint64 code equal the Int terms.
#include <chrono>
#include <cstdio>
#include <string>

#include "core/xy/axis/step_timer.hpp"
#include "models/xy/smt/axis_kernels.hpp"
#include "models/xy/smt/axis_obligations.hpp"
#include "models/xy/smt/modules.hpp"

namespace ap::model::smt {
namespace {

Outcome decide_int(z3::context& c, const z3::expr& hyp, const z3::expr& goal, unsigned timeout_ms,
                   const z3::expr& f, const std::string& name) {
  Outcome out;
  const auto t0 = std::chrono::steady_clock::now();
  z3::solver s(c);
  if (timeout_ms > 0) s.set("timeout", timeout_ms);
  s.add(hyp);
  s.add(!goal);
  const auto r = s.check();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r == z3::unsat) {
    out.verdict = Verdict::Proved;
  } else if (r == z3::sat) {
    out.verdict = Verdict::Failed;
    ReplayCase k;
    k.obligation = name;
    k.kind = "timer";
    k.timer_f = static_cast<unsigned>(s.get_model().eval(f, true).get_numeral_uint64());
    out.counterexample = "f_hz=" + std::to_string(k.timer_f) + "\n    replay case written to " + write_case(k);
  } else {
    out.verdict = Verdict::Unknown;
    out.counterexample = s.reason_unknown();
  }
  return out;
}

struct TimerVars {
  z3::context& c;
  z3::expr f;
  xy_axis::Checks checks;
  xy_axis::TimerTerms t;
  explicit TimerVars(z3::context& ctx)
      : c(ctx), f(ctx.int_const("f_hz")),
        t(xy_axis::step_timer(xy_axis::Arith(ctx, xy_axis::Sem::Int, &checks, ctx.bool_val(true), true), f)) {}
  z3::expr pre() const { return f >= 1 && f <= static_cast<int>(ap::xy_axis::kStepFreqMax); }
};

}  // namespace

void add_timer_obligations(ObligationList& out) {
  out.push_back({"timer.no_wrap",
                 "QF_NIA, every f in [1, 4e7]: every uint64 intermediate of step_timer in [0, 2^64), divisors > 0",
                 [](unsigned ms) {
                   TimerVars v(shared_context());
                   z3::expr all = v.c.bool_val(true);
                   for (const auto& x : v.checks) all = all && z3::implies(x.guard, x.cond);
                   return decide_int(v.c, v.pre(), all, ms, v.f, "timer.no_wrap");
                 }});
  out.push_back({"timer.registers_16bit", "QF_NIA, every f in [1, 4e7]: 0 <= PSC <= 65535 and 0 <= ARR <= 65535",
                 [](unsigned ms) {
                   TimerVars v(shared_context());
                   const z3::expr goal = v.t.psc >= 0 && v.t.psc <= 65535 && v.t.arr >= 0 && v.t.arr <= 65535;
                   return decide_int(v.c, v.pre(), goal, ms, v.f, "timer.registers_16bit");
                 }});
  out.push_back({"timer.frequency_error",
                 "QF_NIA, every f in [1, 4e7]: f <= f_real < f*(ARR+2)/(ARR+1), i.e. "
                 "f*(PSC+1)*(ARR+1) <= f_clk < f*(PSC+1)*(ARR+2); ARR+1 >= 32768 below 1221 Hz; PSC = 0 above",
                 [](unsigned ms) {
                   TimerVars v(shared_context());
                   const z3::expr P = v.t.psc + 1, A = v.t.arr + 1;
                   const z3::expr clk = v.c.int_val(static_cast<int>(ap::xy_axis::kTimerClockHz));
                   const z3::expr goal = v.f * P * A <= clk && clk < v.f * P * (A + 1) &&
                                         z3::implies(v.f < 1221, A >= 32768) && z3::implies(v.f >= 1221, v.t.psc == 0);
                   return decide_int(v.c, v.pre(), goal, ms, v.f, "timer.frequency_error");
                 }});
}

}  // namespace ap::model::smt
