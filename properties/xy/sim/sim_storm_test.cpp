// Random storms (docs/protocol.md "Delivery", docs/sim.md "Storms"): random command sequences
// (gotos, relative moves, jogs, stops, bursts, parameter changes, saves) on 16 or 32 boards at
// once (below), each board its own storm, under one fault mix per run, through the simulated PC and boards over
// the DDS bus. Oracles, per board:
//   - the simulated PC's own checks (docs/sim.md): the board took exactly the frames the client
//     saw answered, one for one and in order (exactly once); each stop went out in the next new
//     frame and brought the axis to rest within a ramp time of its answer; the echo model agreed
//     with every echo; the axis safety properties (speed, DIR only at the start speed, endstops);
//   - every command was delivered, or cancelled by a later stop of its axis (no retry budget ran
//     out, nothing was reported lost);
//   - the final position of each axis is the model's for the confirmed commands: the last goto
//     of the storm plus the relative move confirmed after it (a move repeated would add twice);
//   - no lost steps (mechanics model).
// A failing board is shrunk (its actions cut down while it still fails) into a scenario written to
// scenarios/xy/regressions/, which SimScenario/Bundled then replays.
//
// The gate (AP_STORM_SEEDS unset) runs one seed per mix on 16 boards: 8 mixes x 16 = 128 storms.
// AP_STORM_SEEDS=N (the nightly run, ci/nightly-fuzz: 16) runs N seeds per mix on 32 boards each,
// 8 x 32 x N storms (4096 at 16). A run's time grows with its boards (docs/gate-time.md), and
// the rare delivery bug is the nightly's to find, the gate keeps every mix and the seq wrap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sim/xy/scenario.hpp"
#include "sim/xy/run.hpp"

namespace sc = ap::sim::xy::scenario;
namespace cl = ap::xy_client;

namespace {

constexpr std::uint32_t kBoardsGate = 16;     // AP_STORM_SEEDS unset: the gate's run
constexpr std::uint32_t kBoardsNightly = 32;  // AP_STORM_SEEDS=N: the nightly's long runs

struct Mix {
  const char* name;
  std::vector<std::string> faults;
};

// Each fault alone at 30 %, delay with jitter, and combined (docs/protocol.md "Delivery": the
// guarantee holds for each up to 30 %, alone and combined).
const std::vector<Mix>& mixes() {
  static const std::vector<Mix> m = {
      {"drop30", {"drop 30 %"}},
      {"corrupt30", {"corrupt 30 %"}},
      {"duplicate30", {"duplicate 30 %"}},
      {"reorder30", {"reorder 30 %"}},
      {"delay", {"delay 5 ms jitter 5 ms"}},
      {"mixed10", {"drop 10 %", "corrupt 10 %", "duplicate 10 %", "reorder 10 %", "delay 3 ms jitter 2 ms"}},
      {"all30", {"drop 30 %", "corrupt 30 %", "duplicate 30 %", "reorder 30 %", "delay 3 ms jitter 2 ms"}},
      {"drop30_corrupt30", {"drop 30 %", "corrupt 30 %"}},
  };
  return m;
}

struct BoardStorm {
  std::vector<std::string> actions;  // "at T ACTION" without the board target
  std::int64_t final_x_um = 0, final_y_um = 0;
};

std::string at(std::int64_t t_ms, const std::string& what) {
  std::ostringstream o;
  o << "at " << t_ms / 1000 << "." << (t_ms % 1000 < 100 ? (t_ms % 1000 < 10 ? "00" : "0") : "") << t_ms % 1000 << " s "
    << what;
  return o.str();
}

std::string mm(std::int64_t um) { return std::to_string(um) + " um"; }

// One board's storm: random commands from 0.5 s to 8 s, then the final block: a goto per axis at
// 9 s and a relative move per axis at 15 s (the goto's motion, at most ~30 mm at 10 mm/s or more,
// is over by then), end 18 s.
BoardStorm make_storm(std::mt19937_64& rng) {
  BoardStorm s;
  auto pick = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  const char* axes[] = {"x", "y"};
  s.actions.push_back(at(0, "set speed fast " + std::to_string(pick(10, 15)) + " mm/s"));
  s.actions.push_back(at(0, "set accel " + std::to_string(pick(20, 40)) + " mm/s2"));
  std::int64_t t = 500;
  while (t < 8'000) {
    const std::string a = axes[pick(0, 1)];
    switch (pick(0, 9)) {
      case 0:
      case 1: s.actions.push_back(at(t, "goto " + a + " " + mm(pick(4000, 6000) * 10))); break;
      case 2:
      case 3: s.actions.push_back(at(t, "move " + a + " " + mm(pick(-500, 500) * 10))); break;
      case 4: {  // a held key: jog, then release with a stop
        s.actions.push_back(at(t, "jog " + a + (pick(0, 1) ? " +" : " -") + " slow"));
        s.actions.push_back(at(t + pick(200, 1000), "stop " + a));
        break;
      }
      case 5: s.actions.push_back(at(t, "stop " + a)); break;
      case 6: {  // a burst: several commands at once, then a stop of one axis
        for (int k = 0, n = static_cast<int>(pick(2, 4)); k < n; ++k) {
          const std::string b = axes[pick(0, 1)];
          s.actions.push_back(at(t, pick(0, 1) ? "goto " + b + " " + mm(pick(4000, 6000) * 10)
                                               : "move " + b + " " + mm(pick(-300, 300) * 10)));
        }
        s.actions.push_back(at(t, "stop " + a));
        break;
      }
      case 7: s.actions.push_back(at(t, "set speed fast " + std::to_string(pick(10, 15)) + " mm/s")); break;
      case 8: s.actions.push_back(at(t, "set accel " + std::to_string(pick(20, 40)) + " mm/s2")); break;
      default: s.actions.push_back(at(t, "save")); break;
    }
    t += pick(1, 120) * 10;
  }
  // Sorted by time (a jog's stop may lie past the next command); stable keeps same-time order.
  std::stable_sort(s.actions.begin(), s.actions.end(), [](const std::string& l, const std::string& r) {
    return std::stod(l.substr(3)) < std::stod(r.substr(3));
  });
  const std::int64_t gx = pick(4000, 6000) * 10, gy = pick(4000, 6000) * 10;
  const std::int64_t dx = pick(-300, 300) * 10, dy = pick(-300, 300) * 10;
  s.actions.push_back(at(9'000, "goto x " + mm(gx)));
  s.actions.push_back(at(9'000, "goto y " + mm(gy)));
  s.actions.push_back(at(15'000, "move x " + mm(dx)));
  s.actions.push_back(at(15'000, "move y " + mm(dy)));
  s.final_x_um = gx + dx;
  s.final_y_um = gy + dy;
  return s;
}

// The scenario text: boards 0..n-1 with their storms (board b's actions "@b"), or, for a
// shrunk storm, `only` = b: the same number of boards (so board b's links draw the same random
// faults) but actions for board b alone.
std::string scenario_text(const std::string& name, const Mix& mix, std::uint64_t seed, std::uint16_t first_seq,
                          const std::vector<BoardStorm>& storms, std::optional<std::uint32_t> only = std::nullopt) {
  std::ostringstream o;
  o << "scenario " << name << "\ntitle \"storm: " << mix.name << ", seed " << seed << "\"\n";
  o << "boards " << storms.size() << "\nduration 18 s\nseed " << seed << "\nfirst_seq " << first_seq << "\n";
  o << "board ble session\nboard pos x 50 mm\nboard pos y 50 mm\n";
  for (const std::string& f : mix.faults) o << "fault " << f << "\n";
  // The scenario language wants actions in time order: merged over the boards (stable, so the
  // order of one board's same-time actions is kept).
  std::vector<std::pair<double, std::string>> lines;
  for (std::uint32_t b = 0; b < storms.size(); ++b) {
    if (only && *only != b) continue;
    for (const std::string& a : storms[b].actions) {
      const std::size_t sp = a.find(" s ");
      lines.emplace_back(std::stod(a.substr(3)), a.substr(0, sp + 3) + "@" + std::to_string(b) + " " + a.substr(sp + 3));
    }
  }
  std::stable_sort(lines.begin(), lines.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
  for (const auto& l : lines) o << l.second << "\n";
  for (std::uint32_t b = 0; b < storms.size(); ++b) {
    if (only && *only != b) continue;
    o << "expect end @" << b << " x.pos == " << storms[b].final_x_um << " um tol 1 um\n";
    o << "expect end @" << b << " y.pos == " << storms[b].final_y_um << " um tol 1 um\n";
  }
  o << "expect end x.lost_steps == 0\nexpect end y.lost_steps == 0\n";
  return o.str();
}

// What is wrong with one board's run, beyond the scenario's own failures; empty = nothing.
std::vector<std::string> board_problems(const ap::sim::xy::RunResult& r, std::uint32_t b) {
  std::vector<std::string> p;
  const std::string tag = "board " + std::to_string(b);
  for (const std::string& f : r.failures) {
    if (f.find(tag + ":") != std::string::npos || f.find(tag + " ") != std::string::npos ||
        f.find("@" + std::to_string(b)) != std::string::npos) {
      p.push_back(f);
    }
  }
  const ap::sim::xy::DeliveryStats& d = r.boards.at(b).delivery;
  if (d.given_up != 0) p.push_back(tag + ": " + std::to_string(d.given_up) + " frames ran out of transmissions");
  for (const cl::Report& rep : d.reports) {
    if (!cl::delivered(rep.outcome) && rep.outcome != cl::Outcome::Superseded) {
      p.push_back(tag + ": a command issued at " + std::to_string(rep.issued_us) + " us ended " + cl::to_string(rep.outcome));
    }
  }
  if (d.delivered + static_cast<std::uint32_t>(std::count_if(d.reports.begin(), d.reports.end(), [](const cl::Report& x) {
        return x.outcome == cl::Outcome::Superseded;
      })) != d.submitted) {
    p.push_back(tag + ": " + std::to_string(d.submitted) + " commands submitted, not all settled");
  }
  return p;
}

ap::sim::xy::RunResult run(const std::string& text, const std::string& name) {
  ap::sim::xy::RunOptions o;
  o.out_root = "";
  return ap::sim::xy::run_scenario(sc::parse(text, name + ".scn"), o);
}

// The kind of a problem, so that shrinking keeps the failure it started from.
std::string kind_of(const std::string& problem) {
  for (const char* k : {"delivery", "safety", "echo model", "echo check", "ran out", "ended", "not all settled", ".scn:"}) {
    if (problem.find(k) != std::string::npos) return k;
  }
  return problem;
}

// Cuts board b's random actions down (in halves, then one at a time, while the board still fails
// the same way; the final goto/move block stays, the expectations rest on it) and writes the
// smallest failing storm to scenarios/xy/regressions/.
std::string shrink(const Mix& mix, std::uint64_t seed, std::uint16_t first_seq, std::vector<BoardStorm> storms,
                   std::uint32_t b, const std::string& kind) {
  const std::string name = std::string("storm_") + mix.name + "_" + std::to_string(seed) + "_" + std::to_string(b);
  // Boards past b go: board b's links draw from a random stream keyed by its index alone.
  storms.resize(b + 1);
  int runs = 0;  // a bound on the reruns: a planted bug may fail every storm, and each rerun costs ~8 s
  auto fails = [&](const std::vector<BoardStorm>& st) {
    if (++runs > 24) return false;
    for (const std::string& p : board_problems(run(scenario_text(name, mix, seed, first_seq, st, b), name), b)) {
      if (kind_of(p) == kind) return true;
    }
    return false;
  };
  constexpr std::size_t kFinal = 4;
  std::vector<std::string>& acts = storms[b].actions;
  for (std::size_t chunk = (acts.size() - kFinal) / 2; chunk >= 1; chunk /= 2) {
    for (std::size_t i = 0; i + chunk + kFinal <= storms[b].actions.size();) {
      std::vector<BoardStorm> trial = storms;
      auto& ta = trial[b].actions;
      ta.erase(ta.begin() + static_cast<std::ptrdiff_t>(i), ta.begin() + static_cast<std::ptrdiff_t>(i + chunk));
      if (fails(trial)) {
        storms = trial;
      } else {
        i += chunk;
      }
    }
    if (chunk == 1) break;
  }
  const std::string path = std::string(AP_SOURCE_DIR) + "/scenarios/xy/regressions/" + name + ".scn";
  std::ofstream(path) << "# A storm that failed (properties/xy/sim/sim_storm_test.cpp), shrunk; it must pass once fixed.\n"
                      << scenario_text(name, mix, seed, first_seq, storms, b);
  return path;
}

std::uint64_t seeds_per_mix() {
  const char* e = std::getenv("AP_STORM_SEEDS");
  return e != nullptr && std::atoi(e) > 0 ? static_cast<std::uint64_t>(std::atoi(e)) : 1U;
}

std::uint32_t boards_per_run() {
  const char* e = std::getenv("AP_STORM_SEEDS");
  return e != nullptr && std::atoi(e) > 0 ? kBoardsNightly : kBoardsGate;
}

}  // namespace

class Storm : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Storm, EveryCommandTakesEffectExactlyOnce) {
  const Mix& mix = mixes().at(GetParam());
  std::uint64_t storms = 0, faults = 0, frames = 0, commands = 0, violations = 0;
  const std::uint32_t boards = boards_per_run();
  for (std::uint64_t seed = 1; seed <= seeds_per_mix(); ++seed) {
    std::mt19937_64 rng(seed * 7919U + GetParam());
    // Start near the end of the seq space so that every storm wraps from 999 to 0.
    const auto first_seq = static_cast<std::uint16_t>(std::uniform_int_distribution<int>(960, 999)(rng));
    std::vector<BoardStorm> st;
    for (std::uint32_t b = 0; b < boards; ++b) st.push_back(make_storm(rng));
    const std::string name = std::string("storm_") + mix.name + "_" + std::to_string(seed);
    const ap::sim::xy::RunResult r = run(scenario_text(name, mix, seed, first_seq, st), name);
    ASSERT_EQ(r.boards.size(), boards);
    for (std::uint32_t b = 0; b < boards; ++b) {
      ++storms;
      const ap::sim::xy::BoardVerdict& v = r.boards[b];
      for (const ap::sim::xy::LinkStats* l : {&v.to_board, &v.to_pc}) {
        faults += l->dropped + l->corrupted + l->duplicated + l->reordered + l->delayed;
      }
      frames += v.delivery.new_frames + v.delivery.retransmissions;
      commands += v.delivery.submitted;
      EXPECT_GT(first_seq + v.delivery.frames_taken, 1000U) << "board " << b << ": the storm must cross the seq wrap";
      const std::vector<std::string> p = board_problems(r, b);
      if (p.empty()) continue;
      ++violations;
      std::string all;
      for (const std::string& x : p) all += "\n  " + x;
      // The first failing board of a run is shrunk into a regression scenario; the rest only
      // reported (one reproducer is what a fix needs, and shrinking costs reruns).
      ADD_FAILURE() << mix.name << " seed " << seed << ", board " << b << ":" << all
                    << (violations == 1 ? "\n  shrunk to " + shrink(mix, seed, first_seq, st, b, kind_of(p.front())) : "");
    }
    if (!r.pass && violations == 0) ADD_FAILURE() << ap::sim::xy::format_report(sc::parse(scenario_text(name, mix, seed, first_seq, st)), r);
  }
  std::cout << "storms " << mix.name << ": " << storms << " storms, " << commands << " commands, " << frames
            << " frames sent, " << faults << " faults injected, " << violations << " violations\n";
  EXPECT_EQ(violations, 0U);
}

INSTANTIATE_TEST_SUITE_P(SimStorm, Storm, ::testing::Range<std::size_t>(0, mixes().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& i) { return std::string(mixes().at(i.param).name); });
