// axisproof sim: a profile's simulated PC and boards over the DDS test bus (docs/sim.md).
//   axisproof sim board [--profile P] [--domain N] [--boards K] [--out DIR]   boards only, until the PC shuts them down
//   axisproof sim run [--profile P] scenarios/NAME [--realtime] [--domain N --join] [--out ROOT] [--step-ms MS]
#include "cli.hpp"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "profile.hpp"

namespace ap::cli {
namespace {

// NAME, NAME.scn, or either under the tree or the profile's scenario folder.
std::string scenario_path(const std::string& arg, const Profile& p) {
  namespace fs = std::filesystem;
  const std::string dir = source_dir() + "/" + scenarios_dir(p) + "/";
  for (const std::string& c : {arg, arg + ".scn", source_dir() + "/" + arg, source_dir() + "/" + arg + ".scn",
                               dir + arg, dir + arg + ".scn"}) {
    if (fs::is_regular_file(c)) return c;
  }
  return arg;
}

}  // namespace

int sim_run_main(const std::function<SimRunVerdict()>& run) {
  try {
    const SimRunVerdict v = run();
    if (!v.out_dir.empty()) std::cout << "  outputs: " << v.out_dir << "/{trace.csv,waveforms.vcd,plots.svg,report.txt}\n";
    return v.pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof sim run: %s\n", e.what());
    return 2;
  }
}

int host_boards(const SimBoardArgs& a, std::string_view label, const BoardServer& serve) {
  try {
    dds::use_loopback_config(false);
    auto pp = dds::make_participant(a.domain);
    std::vector<std::thread> threads;
    std::vector<int> rc(a.boards, -1);
    std::fprintf(stderr, "axisproof sim board --profile %.*s: %u board(s) on DDS domain %u (loopback only)\n",
                 static_cast<int>(label.size()), label.data(), a.boards, a.domain);
    for (std::uint32_t b = 0; b < a.boards; ++b) {
      threads.emplace_back([&, b] {
        try {
          rc[b] = serve(pp, b, b == 0 ? a.out : std::string(), std::chrono::seconds(a.idle_s));
        } catch (const std::exception& e) {
          std::fprintf(stderr, "board %u: %s\n", b, e.what());
          rc[b] = 3;
        }
      });
    }
    for (auto& t : threads) t.join();
    int status = 0;
    for (std::uint32_t b = 0; b < a.boards; ++b) {
      if (rc[b] != 0) {
        std::fprintf(stderr, "board %u ended with code %d (2 = idle timeout)\n", b, rc[b]);
        status = 1;
      }
    }
    return status;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof sim board: %s\n", e.what());
    return 1;
  }
}

void add_sim(CLI::App& app) {
  auto* sub = app.add_subcommand("sim", "Run a profile's simulated PC and board over the DDS test bus");
  sub->require_subcommand(1);

  auto* board = sub->add_subcommand("board", "Run simulated boards on a DDS domain until the PC shuts them down");
  static SimBoardArgs b;
  static std::string board_profile;
  board->add_option("--domain", b.domain, "DDS domain id")->default_val(0);
  board->add_option("--boards", b.boards, "Boards hosted by this process (ids 0..K-1)")->default_val(1);
  board->add_option("--out", b.out, "Output directory of board 0 (trace.csv, waveforms.vcd, plots.svg)");
  board->add_option("--idle-timeout", b.idle_s, "Exit after this many seconds without a command")->default_val(600);
  add_profile_option(board, board_profile);
  board->final_callback([] {
    const Profile* p = find_profile(board_profile);
    if (p->sim_board == nullptr) {
      std::fprintf(stderr, "axisproof sim board: profile %s has no simulated board yet (docs/profiles.md)\n", board_profile.c_str());
      exit_status() = 2;
      return;
    }
    exit_status() = p->sim_board(b);
  });

  auto* run = sub->add_subcommand("run", "Run a scenario: the simulated PC (and, unless --join, the boards in-process)");
  static SimRunArgs r;
  static std::string run_profile;
  run->add_option("scenario", r.scenario, "Scenario file (scenarios/NAME, with or without .scn)")->required();
  run->add_flag("--realtime", r.realtime, "Virtual time follows the wall clock (for watching)");
  run->add_option("--domain", r.domain, "DDS domain id (default: a free one is claimed)");
  run->add_flag("--join", r.join, "Join boards already running (axisproof sim board --domain N)");
  run->add_option("--out", r.out_root, "Output root; board 0's files go to ROOT/NAME/ (default out/sim/<profile>)");
  run->add_option("--target", r.target, "host: the core in this process; qemu: the profile's Cortex-M4 image under QEMU (docs/qemu.md)")
      ->default_val("host")
      ->check(CLI::IsMember({"host", "qemu"}));
  run->add_option("--step-ms", r.step_ms, "Lockstep granularity in ms (telemetry sampling)")->default_val(10);
  add_profile_option(run, run_profile);
  run->final_callback([] {
    const Profile* p = find_profile(run_profile);
    if (p->sim_run == nullptr) {
      std::fprintf(stderr, "axisproof sim run: profile %s has no simulated board yet (docs/profiles.md)\n", run_profile.c_str());
      exit_status() = 2;
      return;
    }
    SimRunArgs a = r;
    a.scenario = scenario_path(r.scenario, *p);
    // Each profile's runs under out/sim/<profile>/NAME (the gate shows a profile's plots from
    // there); a root given with --out is used as given.
    if (a.out_root.empty()) a.out_root = "out/sim/" + std::string(p->name);
    exit_status() = p->sim_run(a);
  });
}

}  // namespace ap::cli
