// The lockstep run of one scenario against one or more simulated boards, the same for the
// profiles' end-to-end layers (their docs/*-sim.md pages; the lockstep of docs/dds.md): claim a
// DDS domain, host each board on a thread unless they run elsewhere (--join), drive them from
// the PC side in virtual time, shut them down and write the report. Each profile keeps its own
// PC side (what it sends, reads and judges, its fault links and pacing) and its own board.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "pc/dds/bus.hpp"
#include "pc/dds/domain.hpp"
#include "sim/serve_loop.hpp"

namespace ap::sim {

// The PC side's end of the bus to board 0: plain lockstep steps, flagged commands (environment,
// shutdown) with their echoes, and the count of round trips.
class LockstepLink {
 public:
  // `who` names the run in errors (the profile's name).
  LockstepLink(std::string who, std::uint32_t domain)
      : who_(std::move(who)), pp_(dds::make_participant(domain)), ep_(std::make_unique<dds::PcEndpoint>(pp_, 0)) {}

  void wait_board() {
    if (!ep_->wait_matched(std::chrono::seconds(20))) {
      throw dds::Error(who_ + " run: the board did not appear on the bus within 20 s");
    }
  }

  dds::EchoSample step(std::span<const std::uint8_t> bytes, std::int64_t t) {
    dds::EchoSample e = ep_->step(bytes, static_cast<std::uint64_t>(t));
    ++round_trips_;
    return e;
  }

  // A flagged command and its echo; PcEndpoint::step sends unflagged.
  dds::EchoSample flagged(std::span<const std::uint8_t> bytes, std::int64_t t, std::uint32_t flags) {
    const std::uint64_t seq = ep_->send(bytes, static_cast<std::uint64_t>(t), flags);
    ++round_trips_;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      auto e = ep_->take_echo(std::max(left, std::chrono::milliseconds(0)));
      if (!e) throw dds::Error(who_ + " run: the board did not answer bus command " + std::to_string(seq));
      if (e->cmd_seq == seq) return std::move(*e);
    }
  }

  // An environment command (dds::kFlagEnv) and the board's text reply.
  std::string env(const std::string& text, std::int64_t t) {
    const dds::EchoSample e =
        flagged({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, t, dds::kFlagEnv);
    return {e.bytes.begin(), e.bytes.end()};
  }

  // The safety verdict of the board's summary (its `violations=N`, negative when the summary
  // lacked it) as failures: the first 50 violations in full, the rest counted.
  void safety_failures(std::int64_t violations, std::int64_t t, std::vector<std::string>& failures) {
    if (violations < 0) failures.push_back("the board gave no summary");
    for (std::int64_t i = 0; i < std::min<std::int64_t>(violations, 50); ++i) {
      failures.push_back("safety: " + env("violation " + std::to_string(i), t));
    }
    if (violations > 50) failures.push_back("safety: " + std::to_string(violations - 50) + " more violations");
  }

  // Shuts the board down at t (it writes its outputs) and closes the PC side's result: the
  // round trips, the virtual time t and the wall time since wall0.
  template <class Result>
  Result finish(Result r, std::int64_t t, std::chrono::steady_clock::time_point wall0) {
    (void)flagged({}, t, dds::kFlagShutdown);
    r.bus_round_trips = round_trips_;
    r.vtime_us = t;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    return r;
  }


 private:
  std::string who_;
  dds::ParticipantPtr pp_;
  std::unique_ptr<dds::PcEndpoint> ep_;
  std::uint64_t round_trips_ = 0;
};

// "pulses=500 counter=16000 ..." (a board's env replies) -> the integer fields; words without
// '=' and values that are not integers of up to 18 characters are dropped.
inline std::map<std::string, std::int64_t> env_fields(const std::string& text) {
  std::map<std::string, std::int64_t> f;
  std::istringstream in(text);
  std::string kv;
  while (in >> kv) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos) continue;
    const std::string v = kv.substr(eq + 1);
    if (v.empty() || v.size() > 18 || v.find_first_not_of("-0123456789") != std::string::npos) continue;
    f[kv.substr(0, eq)] = std::stoll(v);
  }
  return f;
}

// Every lockstep period in (0, duration) and the duration; the profile adds the times its
// actions and expectations name.
inline std::set<std::int64_t> lockstep_times(std::int64_t step_us, std::int64_t duration_us) {
  std::set<std::int64_t> t;
  for (std::int64_t k = step_us; k < duration_us; k += step_us) t.insert(k);
  t.insert(duration_us);
  return t;
}

// The boards a run hosts when it does not join them, and how its verdict and log name them.
struct LockstepBoards {
  std::uint32_t count = 1;          // boards 0..count-1 on the bus, each served on its own thread
  bool numbered = false;            // "board N did not shut down cleanly", log "board N: ..." (else
                                    // "the board ...", log "WHO board: ...")
  bool report_when_joined = false;  // a joined run writes out_root/NAME/report.txt too (its
                                    // boards' outputs are the other process's)
};

// Runs one scenario. `serve(participant, board, out_dir, stop)` serves board number `board` (the
// profile's serve_board, returning 0 on an orderly shutdown; out_dir is the run's, the profile
// decides which board writes there); `run_pc(domain)` is the PC side, returning the profile's
// RunResult (pass, failures, domain, out_dir); `report(result)` the verdict as text, also
// written to out_dir/report.txt. The out folder is emptied first unless the run joins boards
// that run elsewhere. Options: out_root, step_us, domain, join, log (the profiles' RunOptions).
template <class Options, class Serve, class RunPc, class Report>
auto run_lockstep(const std::string& who, const std::string& name, const Options& opt, const LockstepBoards& boards,
                  Serve serve, RunPc run_pc, Report report) {
  if (opt.step_us <= 0) throw std::runtime_error(who + " run: the lockstep period must be positive");
  dds::use_loopback_config(false);
  std::optional<dds::DomainLease> lease;
  const std::uint32_t domain = dds::fixed_or_claimed(opt.domain, lease);
  const std::string out_dir = opt.out_root.empty() ? std::string() : opt.out_root + "/" + name;
  if (!out_dir.empty() && !opt.join) {
    // A stale trace of an earlier run must not pass for this one's.
    std::filesystem::remove_all(out_dir);
  }
  const auto board_name = [&](std::uint32_t b) { return boards.numbered ? "board " + std::to_string(b) : std::string(); };
  std::atomic<bool> stop{false};
  std::vector<std::thread> threads;
  std::vector<int> rc(opt.join ? 0 : boards.count, 0);
  dds::ParticipantPtr board_pp;
  const auto join_all = [&] {
    for (auto& th : threads) {
      if (th.joinable()) th.join();
    }
  };
  decltype(run_pc(domain)) r;
  try {
    if (!opt.join) {
      board_pp = dds::make_participant(domain);
      for (std::uint32_t b = 0; b < boards.count; ++b) {
        threads.emplace_back([&, b] {
          try {
            rc[b] = serve(board_pp, b, out_dir, &stop);
          } catch (const std::exception& e) {
            rc[b] = 3;
            if (opt.log != nullptr) *opt.log << (boards.numbered ? board_name(b) : who + " board") << ": " << e.what() << '\n';
          }
        });
      }
    }
    r = run_pc(domain);
  } catch (...) {
    stop = true;
    join_all();
    throw;
  }
  join_all();
  for (std::uint32_t b = 0; b < rc.size(); ++b) {
    if (rc[b] == 0) continue;
    r.failures.push_back((boards.numbered ? board_name(b) : std::string("the board")) + " did not shut down cleanly (code " +
                         std::to_string(rc[b]) + ")");
  }
  r.pass = r.failures.empty();
  r.domain = domain;
  r.out_dir = opt.join ? std::string() : out_dir;
  const std::string report_dir = opt.join && !boards.report_when_joined ? std::string() : out_dir;
  if (!report_dir.empty()) {
    std::filesystem::create_directories(report_dir);
    std::ofstream(report_dir + "/report.txt") << report(r);
  }
  return r;
}

// The run of one board (board 0): `serve(participant, out_dir, stop)`.
template <class Options, class Serve, class RunPc, class Report>
auto run_lockstep(const std::string& who, const std::string& name, const Options& opt, Serve serve, RunPc run_pc,
                  Report report) {
  return run_lockstep(
      who, name, opt, LockstepBoards{},
      [&](const dds::ParticipantPtr& pp, std::uint32_t, const std::string& out_dir, const std::atomic<bool>* stop) {
        return serve(pp, out_dir, stop);
      },
      std::move(run_pc), std::move(report));
}

}  // namespace ap::sim
