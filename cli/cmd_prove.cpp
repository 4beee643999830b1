// axisproof prove: discharges a profile's proof obligations (the XY profile's: models/smt) with Z3.
// Exit 0 only when every selected obligation is PROVED; UNKNOWN (e.g. a timeout) fails too,
// because an obligation that was not proved is not a proof.
#include "cli.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "models/smt/obligation.hpp"
#include "profile.hpp"

namespace ap::cli {

namespace {

struct ProveOptions {
  std::string profile;
  std::vector<std::string> only;
  // Generous: the slowest obligation takes ~8 s on a loaded 2-core machine, and a timeout is
  // UNKNOWN, which fails the gate (the suite as a whole takes 20-40 s).
  double timeout_s = 60.0;
};

bool selected(const std::string& name, const std::vector<std::string>& only) {
  if (only.empty()) return true;
  for (const auto& o : only) {
    // An exact name, or a prefix such as "tmc2130." or "tmc2130.CHOPCONF".
    if (name == o || name.rfind(o, 0) == 0) return true;
  }
  return false;
}

int prove(const ProveOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<model::smt::Obligation> chosen;
  const Profile* p = find_profile(opt.profile);
  if (p->obligations == nullptr) {
    std::fprintf(stderr, "axisproof prove: profile %s has no proof obligations yet (docs/profiles.md)\n", opt.profile.c_str());
    return 1;
  }
  for (auto& o : p->obligations()) {
    if (selected(o.name, opt.only)) chosen.push_back(std::move(o));
  }
  if (chosen.empty()) {
    std::fprintf(stderr, "axisproof prove: no obligation matches --only\n");
    return 1;
  }
  const auto timeout_ms = static_cast<unsigned>(opt.timeout_s * 1000.0);
  std::vector<model::smt::Outcome> outcomes;
  std::size_t width = 10;
  for (const auto& o : chosen) width = std::max(width, o.name.size());
  const int w = static_cast<int>(width);
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const auto& o = chosen[i];
    outcomes.push_back(model::smt::run(o, timeout_ms));
    const auto& r = outcomes.back();
    std::printf("[%zu/%zu] %-*s %s %.3f s\n", i + 1, chosen.size(), w, o.name.c_str(),
                model::smt::verdict_name(r.verdict), r.seconds);
    if (r.verdict != model::smt::Verdict::Proved) {
      std::printf("    %s: %s\n", r.verdict == model::smt::Verdict::Failed ? "counterexample" : "reason",
                  r.counterexample.c_str());
    }
    std::fflush(stdout);
  }
  std::size_t proved = 0, failed = 0, unknown = 0;
  std::printf("\n%-*s  %-7s  %8s  %s\n", w, "obligation", "result", "seconds", "method");
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const auto& r = outcomes[i];
    std::printf("%-*s  %-7s  %8.3f  %s\n", w, chosen[i].name.c_str(), model::smt::verdict_name(r.verdict),
                r.seconds, chosen[i].method.c_str());
    proved += r.verdict == model::smt::Verdict::Proved;
    failed += r.verdict == model::smt::Verdict::Failed;
    unknown += r.verdict == model::smt::Verdict::Unknown;
  }
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    if (outcomes[i].verdict == model::smt::Verdict::Failed) {
      std::printf("\nFAILED %s\n  counterexample: %s\n", chosen[i].name.c_str(),
                  outcomes[i].counterexample.c_str());
    }
  }
  std::printf("\n%zu obligations: %zu proved, %zu failed, %zu unknown (%.2f s wall)\n", chosen.size(),
              proved, failed, unknown, seconds_since(start));
  return proved == chosen.size() ? 0 : 1;
}

}  // namespace

void add_prove(CLI::App& app) {
  auto opt = std::make_shared<ProveOptions>();
  auto* sub = app.add_subcommand("prove", "Prove a profile's obligations with Z3");
  add_profile_option(sub, opt->profile);
  sub->add_option("--only", opt->only, "Only obligations with this name or name prefix (repeatable)");
  sub->add_option("--timeout", opt->timeout_s, "Z3 time limit per obligation, seconds (default 60)")
      ->check(CLI::PositiveNumber);
  sub->final_callback([opt] { exit_status() = prove(*opt); });
}

}  // namespace ap::cli
