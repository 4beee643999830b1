// axisproof prove: discharges a profile's proof obligations (its entry's, on the models/smt kit) with Z3.
// Exit 0 only when every selected obligation is PROVED; UNKNOWN (e.g. a timeout) fails too,
// because an obligation that was not proved is not a proof.
#include "cli.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
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
  int jobs = 1;
};

bool selected(const std::string& name, const std::vector<std::string>& only) {
  if (only.empty()) return true;
  for (const auto& o : only) {
    // An exact name, or a prefix such as "tmc2130." or "tmc2130.CHOPCONF".
    if (name == o || name.rfind(o, 0) == 0) return true;
  }
  return false;
}

// --jobs N: the obligations are dealt round-robin to N processes. Processes, not threads: all
// obligations share one Z3 context (models/smt/obligation.hpp), which is not thread-safe, and
// a fork gives each worker its own copy. A worker prints its progress lines itself and sends its
// outcomes to the first process over a pipe; the table is printed in the registry's order.
struct WireOutcome {
  std::uint32_t index;
  std::int32_t verdict;
  double seconds;
  std::uint32_t text_len;
};

bool write_all(int fd, const void* p, std::size_t n) {
  const auto* b = static_cast<const char*>(p);
  while (n > 0) {
    const ssize_t w = ::write(fd, b, n);
    if (w <= 0) return false;
    b += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

bool read_all(int fd, void* p, std::size_t n) {
  auto* b = static_cast<char*>(p);
  while (n > 0) {
    const ssize_t r = ::read(fd, b, n);
    if (r <= 0) return false;
    b += r;
    n -= static_cast<std::size_t>(r);
  }
  return true;
}

// Runs obligation i and prints its progress line (and its reason or counterexample) as one write.
model::smt::Outcome run_one(const std::vector<model::smt::Obligation>& chosen, std::size_t i, unsigned timeout_ms,
                            int w) {
  const auto& o = chosen[i];
  model::smt::Outcome r = model::smt::run(o, timeout_ms);
  std::string line(static_cast<std::size_t>(w) + o.name.size() + 64, '\0');
  line.resize(static_cast<std::size_t>(std::snprintf(line.data(), line.size(), "[%zu/%zu] %-*s %s %.3f s\n", i + 1,
                                                     chosen.size(), w, o.name.c_str(),
                                                     model::smt::verdict_name(r.verdict), r.seconds)));
  if (r.verdict != model::smt::Verdict::Proved) {
    line += std::string("    ") + (r.verdict == model::smt::Verdict::Failed ? "counterexample" : "reason") + ": " +
            r.counterexample + "\n";
  }
  std::fputs(line.c_str(), stdout);
  std::fflush(stdout);
  return r;
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
  std::vector<model::smt::Outcome> outcomes(chosen.size());
  std::vector<bool> have(chosen.size(), false);
  std::size_t width = 10;
  for (const auto& o : chosen) width = std::max(width, o.name.size());
  const int w = static_cast<int>(width);
  const std::size_t jobs = std::min(static_cast<std::size_t>(opt.jobs), chosen.size());
  struct Worker {
    pid_t pid;
    int fd;
  };
  std::vector<Worker> workers;
  std::fflush(stdout);
  for (std::size_t k = 1; k < jobs; ++k) {
    int fds[2];
    if (::pipe(fds) != 0) break;  // fewer workers: the first process takes their share
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      break;
    }
    if (pid == 0) {
      ::close(fds[0]);
      for (const Worker& other : workers) ::close(other.fd);
      bool ok = true;
      for (std::size_t i = k; i < chosen.size() && ok; i += jobs) {
        const model::smt::Outcome r = run_one(chosen, i, timeout_ms, w);
        const WireOutcome h{static_cast<std::uint32_t>(i), static_cast<std::int32_t>(r.verdict), r.seconds,
                            static_cast<std::uint32_t>(r.counterexample.size())};
        ok = write_all(fds[1], &h, sizeof h) && write_all(fds[1], r.counterexample.data(), r.counterexample.size());
      }
      std::fflush(stdout);
      ::_exit(ok ? 0 : 1);  // no atexit handlers: they belong to the first process
    }
    ::close(fds[1]);
    workers.push_back({pid, fds[0]});
  }
  // The first process takes share 0 and the share of any worker that could not be started.
  const std::size_t started = workers.size() + 1;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    if (i % jobs == 0 || i % jobs >= started) {
      outcomes[i] = run_one(chosen, i, timeout_ms, w);
      have[i] = true;
    }
  }
  for (const Worker& wk : workers) {
    WireOutcome h{};
    while (read_all(wk.fd, &h, sizeof h) && h.index < chosen.size()) {
      std::string text(h.text_len, '\0');
      if (!read_all(wk.fd, text.data(), text.size())) break;
      const bool known = h.verdict >= static_cast<std::int32_t>(model::smt::Verdict::Proved) &&
                         h.verdict <= static_cast<std::int32_t>(model::smt::Verdict::Unknown);
      outcomes[h.index] = {known ? static_cast<model::smt::Verdict>(h.verdict) : model::smt::Verdict::Unknown,
                           h.seconds, std::move(text)};
      have[h.index] = true;
    }
    ::close(wk.fd);
    int status = 0;
    ::waitpid(wk.pid, &status, 0);
  }
  // An obligation whose worker died before reporting it is not proved.
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    if (!have[i]) outcomes[i] = {model::smt::Verdict::Unknown, 0.0, "its worker process died before reporting it"};
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
  sub->add_option("--jobs", opt->jobs, "Prove in this many processes at once (default 1)")->check(CLI::Range(1, 64));
  sub->final_callback([opt] { exit_status() = prove(*opt); });
}

}  // namespace ap::cli
