#include "models/smt/obligation.hpp"

#include <chrono>

namespace ap::model::smt {

z3::context& shared_context() {
  static z3::context ctx;
  return ctx;
}

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Proved: return "PROVED";
    case Verdict::Failed: return "FAILED";
    case Verdict::Unknown: return "UNKNOWN";
  }
  return "?";
}

std::string shown_in(const z3::model& m, const Shown& show) {
  std::string text;
  for (const auto& [label, term] : show) {
    if (!text.empty()) text += ' ';
    text += label + "=" + m.eval(term, true).to_string();
  }
  return text;
}

Outcome check_valid(z3::context& ctx, const z3::expr& claim, unsigned timeout_ms, const Shown& show) {
  Outcome out;
  const auto start = std::chrono::steady_clock::now();
  // The QF_BV tactic skips the general solver's set-up, which dominated these small queries.
  z3::solver s(ctx, "QF_BV");
  if (timeout_ms > 0) s.set("timeout", timeout_ms);
  s.add(!claim);
  const z3::check_result r = s.check();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (r == z3::unsat) {
    out.verdict = Verdict::Proved;
  } else if (r == z3::sat) {
    out.verdict = Verdict::Failed;
    out.counterexample = shown_in(s.get_model(), show);
  } else {
    out.verdict = Verdict::Unknown;
    out.counterexample = s.reason_unknown();
  }
  return out;
}

Outcome run(const Obligation& o, unsigned timeout_ms) {
  const auto start = std::chrono::steady_clock::now();
  try {
    return o.check(timeout_ms);
  } catch (const z3::exception& e) {
    Outcome out;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.counterexample = std::string("z3 exception: ") + e.msg();
    return out;
  }
}

}  // namespace ap::model::smt
