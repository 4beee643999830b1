#pragma once
// The proof-obligation registry behind `axisproof prove` and the `proof` ctest label.
//
// This is the kit every profile's proofs use; the obligations are the profiles' own
// (models/<profile>/..., docs/proofs.md). Adding obligations for a module of a profile:
//   1. write `void add_<module>_obligations(ap::model::smt::ObligationList& out)` in the
//      profile's models folder, pushing one Obligation per claim;
//   2. call it from the profile's list of obligations, which its CLI entry names
//      (cli/<profile>/profile.cpp, `Profile::obligations`);
//   3. each check builds its claim in shared_context() and returns check_valid(...).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <z3++.h>

namespace ap::model::smt {

enum class Verdict { Proved, Failed, Unknown };

const char* verdict_name(Verdict v);

struct Outcome {
  Verdict verdict = Verdict::Unknown;
  double seconds = 0.0;
  std::string counterexample;  // Failed: a model; Unknown: Z3's reason
};

struct Obligation {
  std::string name;    // "<module>.<subject>.<property>", unique
  std::string method;  // how it is discharged, e.g. "SMT QF_BV, all 2^32 register values"
  std::function<Outcome(unsigned timeout_ms)> check;
};

using ObligationList = std::vector<Obligation>;

// One Z3 context for all obligations of this process: creating a context costs more than
// most of our queries. Not thread-safe; obligations run one after another.
z3::context& shared_context();

// Decides "claim holds for all values of its free constants": asserts !claim and asks Z3.
// unsat -> Proved; sat -> Failed with the `show` terms evaluated in the model;
// unknown or a Z3 exception -> Unknown. `seconds` is wall time of the solver call.
using Shown = std::vector<std::pair<std::string, z3::expr>>;
Outcome check_valid(z3::context& ctx, const z3::expr& claim, unsigned timeout_ms, const Shown& show);

// The `show` terms evaluated in a counterexample model: "label=value label=value ...".
std::string shown_in(const z3::model& m, const Shown& show);

// Runs an obligation, turning any escaping z3::exception into Unknown.
Outcome run(const Obligation& o, unsigned timeout_ms);

}  // namespace ap::model::smt
