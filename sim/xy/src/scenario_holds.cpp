// An expectation judged against an observed value (docs/scenarios.md "Expectations": OP, `tol`,
// the 1e-9 allowance, `blocked` for every blk_ status). The simulated PC and the parse tests
// call the same function, apart from the parser because it is the runner's verdict, not the
// language's syntax; the comparison itself is the shared kit's (sim/scenario_text.hpp).
#include <stdexcept>
#include <string>
#include <variant>

#include "sim/scenario_text.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::sim::xy::scenario {

bool holds(const Expectation& e, const Value& actual) {
  if (const auto* want = std::get_if<std::string>(&e.value)) {
    const auto* got = std::get_if<std::string>(&actual);
    if (got == nullptr) throw std::invalid_argument("scenario: " + e.subject + " expects a word, got a number");
    // An axis status `blocked` stands for every blocking status the echo names (blk_*).
    const bool is_status = e.subject.size() > 2 && e.subject.substr(1) == ".status";
    const bool same = is_status && *want == "blocked" ? got->rfind("blk_", 0) == 0 : *got == *want;
    if (e.op == Op::Eq) return same;
    if (e.op == Op::Ne) return !same;
    throw std::invalid_argument("scenario: words compare with == or != only");
  }
  const Quantity& want = std::get<Quantity>(e.value);
  const auto* got = std::get_if<Quantity>(&actual);
  if (got == nullptr) throw std::invalid_argument("scenario: " + e.subject + " expects a number, got a word");
  if (got->dim != want.dim) throw std::invalid_argument("scenario: " + e.subject + ": dimension mismatch");
  // Values reach the runner through unit conversions (µsteps to µm); kSlack keeps a value
  // that is exactly on a bound from failing by a rounding error.
  constexpr double kSlack = 1e-9;
  return text::compare_within(got->value, e.op, want.value, e.tol ? e.tol->value : 0.0, kSlack);
}

}  // namespace ap::sim::xy::scenario
