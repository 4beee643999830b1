// axisproof sim: the simulated PC and boards over the DDS test bus (issue 9, docs/sim.md).
//   axisproof sim board [--domain N] [--boards K] [--out DIR]   boards only, until the PC shuts them down
//   axisproof sim run scenarios/NAME [--realtime] [--domain N --join] [--out ROOT] [--step-ms MS]
#include "cli.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "pc/dds/bus.hpp"
#include "sim/scenario.hpp"
#include "sim/run.hpp"

namespace ap::cli {
namespace {

std::string scenario_path(const std::string& arg) {
  namespace fs = std::filesystem;
  for (const std::string& p : {arg, arg + ".scn", source_dir() + "/" + arg, source_dir() + "/" + arg + ".scn",
                               source_dir() + "/scenarios/" + arg, source_dir() + "/scenarios/" + arg + ".scn"}) {
    if (fs::is_regular_file(p)) return p;
  }
  return arg;
}

}  // namespace

void add_sim(CLI::App& app) {
  auto* sub = app.add_subcommand("sim", "Run the simulated PC and board over the DDS test bus");
  sub->require_subcommand(1);

  auto* board = sub->add_subcommand("board", "Run simulated boards on a DDS domain until the PC shuts them down");
  static std::uint32_t board_domain = 0;
  static std::uint32_t board_count = 1;
  static std::string board_out;
  static int idle_s = 600;
  board->add_option("--domain", board_domain, "DDS domain id")->default_val(0);
  board->add_option("--boards", board_count, "Boards hosted by this process (ids 0..K-1)")->default_val(1);
  board->add_option("--out", board_out, "Output directory of board 0 (trace.csv, waveforms.vcd, plots.svg)");
  board->add_option("--idle-timeout", idle_s, "Exit after this many seconds without a command")->default_val(600);
  board->final_callback([] {
    try {
      dds::use_loopback_config(false);
      auto pp = dds::make_participant(board_domain);
      std::vector<std::thread> threads;
      std::vector<int> rc(board_count, -1);
      std::fprintf(stderr, "axisproof sim board: %u board(s) on DDS domain %u (loopback only)\n", board_count, board_domain);
      for (std::uint32_t b = 0; b < board_count; ++b) {
        sim::BoardOptions o;
        o.id = b;
        if (b == 0) o.out_dir = board_out;
        threads.emplace_back([&, o] {
          try {
            rc[o.id] = sim::serve_board(pp, o, std::chrono::seconds(idle_s));
          } catch (const std::exception& e) {
            std::fprintf(stderr, "board %u: %s\n", o.id, e.what());
            rc[o.id] = 3;
          }
        });
      }
      for (auto& t : threads) t.join();
      int status = 0;
      for (std::uint32_t b = 0; b < board_count; ++b) {
        if (rc[b] != 0) {
          std::fprintf(stderr, "board %u ended with code %d (2 = idle timeout)\n", b, rc[b]);
          status = 1;
        }
      }
      exit_status() = status;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "axisproof sim board: %s\n", e.what());
      exit_status() = 1;
    }
  });

  auto* run = sub->add_subcommand("run", "Run a scenario: the simulated PC (and, unless --join, the boards in-process)");
  static std::string scen;
  static bool realtime = false;
  static bool join = false;
  static std::int64_t domain = -1;
  static std::string out_root = "out/sim";
  static int step_ms = 10;
  run->add_option("scenario", scen, "Scenario file (scenarios/NAME, with or without .scn)")->required();
  run->add_flag("--realtime", realtime, "Virtual time follows the wall clock (for watching)");
  run->add_option("--domain", domain, "DDS domain id (default: a free one is claimed)");
  run->add_flag("--join", join, "Join boards already running (axisproof sim board --domain N)");
  run->add_option("--out", out_root, "Output root; board 0's files go to ROOT/NAME/")->default_val("out/sim");
  run->add_option("--step-ms", step_ms, "Lockstep granularity in ms (telemetry sampling)")->default_val(10);
  run->final_callback([] {
    try {
      const std::string path = scenario_path(scen);
      sim::scenario::Scenario s = sim::scenario::parse_file(path);
      sim::RunOptions o;
      o.realtime = realtime || s.timing == sim::scenario::Timing::realtime;
      o.join = join;
      if (join && domain < 0) throw std::runtime_error("--join needs --domain");
      if (domain >= 0) o.domain = static_cast<std::uint32_t>(domain);
      o.out_root = out_root;
      o.step_us = static_cast<std::int64_t>(step_ms) * 1000;
      if (o.step_us <= 0 || s.period_us % o.step_us != 0) throw std::runtime_error("--step-ms must divide the command period");
      o.log = &std::cerr;
      const sim::RunResult r = sim::run_scenario(s, o);
      std::cout << sim::format_report(s, r);
      if (!r.out_dir.empty()) std::cout << "  outputs: " << r.out_dir << "/{trace.csv,waveforms.vcd,plots.svg,report.txt}\n";
      exit_status() = r.pass ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "axisproof sim run: %s\n", e.what());
      exit_status() = 2;
    }
  });
}

}  // namespace ap::cli
