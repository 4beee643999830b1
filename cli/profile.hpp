#pragma once
// A firmware profile: what one controller gives the harness and how the harness's commands
// reach it (docs/profiles.md). `axisproof sim`, `gate`, `fuzz`, `prove` and `frame` take
// `--profile NAME` (default: the profile declared DEFAULT; `--profile list` prints the table)
// and touch the controller only through its entry here. The entry has two halves: what the
// profile's declaration says (profiles/<name>.cmake: its name, controller, MCU, folders and
// coverage folders), filled in by the table CMake generates, and its adapters (its
// cli/<name>/profile.cpp). Its tests and fuzz targets carry its name as a ctest label and in
// fuzz_targets.txt (AP_PROFILE), its mutants sit in ci/mutants/<name>.
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "models/smt/obligation.hpp"
#include "pc/dds/bus.hpp"

namespace ap::cli {

struct SimRunArgs {
  std::string scenario;  // resolved path
  bool realtime = false;
  bool join = false;
  long long domain = -1;  // -1: claim a free one
  std::string out_root;
  int step_ms = 10;
  std::string target = "host";  // host: the core in-process; qemu: the profile's QEMU image (docs/qemu.md)
};

struct SimBoardArgs {
  unsigned domain = 0;
  unsigned boards = 1;
  std::string out;
  int idle_s = 600;
};

// `axisproof panel` (docs/panel.md): the operator's web panel over the DDS bus.
struct PanelArgs {
  std::string target = "host";  // host: boards in-process; qemu: the profile's image runs them
  unsigned boards = 1;
  int port = 8080;              // 0: any free port (printed)
  long long domain = -1;        // -1: claim a free one; with attach: the domain the boards are on
  bool attach = false;          // boards already on the bus (a `sim board` in another process)
  std::string faults;           // the fault link under the panel: scenario `fault` lines, ';' between
};

struct Profile {
  // From the declaration (profiles/<name>.cmake); the adapter leaves them empty.
  std::string_view name;   // the --profile value, the ctest label, the mutants' Profile:
  std::string_view title;
  std::string_view seed;   // where its requirements come from
  std::string_view mcu;    // the target of its size check
  bool is_default = false;
  std::vector<std::string_view> dirs;  // every <layer>/<name> folder it has
  // The folders whose line and branch coverage the gate requires: its core, protocol and PC
  // folders and the shared folders it USES.
  std::vector<std::string_view> coverage_paths;
  // The name its libraries and size table get under out/release (<size_tag>/,
  // <size_tag>-size.{txt,md}); ci/m4-build --profile <name> writes them.
  std::string_view size_tag;

  // Its wire codec (frame decode/encode/doc). decode_* print one line per frame or problem
  // and return true when everything decoded. A part a profile has not brought yet is
  // nullptr (or empty); the commands that need it say so and fail.
  bool (*decode_frames)(const std::vector<std::string>& frames) = nullptr;  // nullptr: no wire protocol
  bool (*decode_stream)(const std::string& capture) = nullptr;
  int (*encode)(const std::vector<std::string>& tokens) = nullptr;  // nullptr: the profile has none
  void (*doc)() = nullptr;                                          // nullptr: the profile has none

  // End to end: its simulated board behind the DDS bus (its bundled scenarios are in
  // scenarios/<name>).
  int (*sim_run)(const SimRunArgs&) = nullptr;
  int (*sim_board)(const SimBoardArgs&) = nullptr;
  // The operator's panel (nullptr: the profile has none yet).
  int (*panel)(const PanelArgs&) = nullptr;

  // Proofs: its obligations, and the tests (a ctest -E regex) that prove exactly those
  // obligations once more, module by module; the gate's proofs stage stands for them.
  std::vector<model::smt::Obligation> (*obligations)() = nullptr;
  std::string_view registry_tests;

  // The scenarios the gate's firmware (QEMU) stage runs on the profile's bootable image
  // (docs/qemu.md); empty: the profile has no image yet and its gate has no such stage.
  std::vector<std::string_view> qemu_scenarios;

  // Subcommands only this profile has (nullptr: none), added to the command line at start.
  void (*add_commands)(CLI::App& app) = nullptr;
};

// `sim board` for any profile: a.boards boards on one loopback participant of a.domain, one
// thread each; `serve` runs one (board 0 writes its outputs to `out`) and returns its code
// (0 after a shutdown, 2 idle timeout). Returns 0 when every board ended with 0.
using BoardServer = std::function<int(const dds::ParticipantPtr&, std::uint32_t id, const std::string& out,
                                      std::chrono::seconds idle)>;
int host_boards(const SimBoardArgs& a, std::string_view label, const BoardServer& serve);

// `axisproof panel` for any profile (cmd_panel.cpp): claims the domain (or takes a.domain),
// hosts a.boards boards on their own threads unless a.attach (`board` serves one until *stop),
// then `serve(domain, ready)` runs the profile's session and web server until Ctrl-C, calling
// `ready(port)` once it listens (the URL and the time since start are printed). Returns the exit
// code: 0 after Ctrl-C, 1 when serving failed.
using PanelBoard = std::function<void(const dds::ParticipantPtr&, std::uint32_t id, const std::atomic<bool>* stop)>;
using PanelServe = std::function<bool(std::uint32_t domain, const std::function<void(int port)>& ready)>;
int panel_main(const PanelArgs& a, std::string_view label, const PanelBoard& board, const PanelServe& serve);

// `sim run` for any profile: `run` parses a.scenario, runs it and prints its report, and
// returns its verdict; this prints where the outputs went and gives the exit code (0 pass,
// 1 fail, 2 error: anything thrown, printed as "axisproof sim run: WHAT").
struct SimRunVerdict {
  bool pass = false;
  std::string out_dir;  // empty: no outputs written
};
int sim_run_main(const std::function<SimRunVerdict()>& run);

// The run options every profile takes alike from `sim run`'s arguments: --join (which needs
// --domain), --domain, --step-ms (each profile checks the period against its own rule), the log.
template <class RunOptions>
void set_run_options(const SimRunArgs& a, RunOptions& o) {
  if constexpr (!requires { o.qemu_image; }) {
    if (a.target != "host") throw std::runtime_error("--target " + a.target + ": this profile has no image (docs/profiles.md)");
  }
  o.join = a.join;
  if (a.join && a.domain < 0) throw std::runtime_error("--join needs --domain");
  if (a.domain >= 0) o.domain = static_cast<std::uint32_t>(a.domain);
  o.step_us = static_cast<std::int64_t>(a.step_ms) * 1000;
  o.log = &std::cerr;
}

// The declared profiles (generated from profiles/*.cmake: <build>/declared_profiles/profiles.cpp).
const std::vector<Profile>& profiles();
// The generated table's constructor: an adapter's entry with its declaration filled in.
Profile declared(Profile adapter, std::string_view name, std::string_view title, std::string_view seed,
                 std::string_view mcu, std::string_view size_tag, bool is_default, std::vector<std::string_view> dirs,
                 std::vector<std::string_view> coverage);
// Its bundled scenarios' folder, from the top of the tree (scenarios/<name>).
std::string scenarios_dir(const Profile& p);
// nullptr for an unknown name (never after add_profile_option accepted it).
const Profile* find_profile(std::string_view name);

// The profile declared DEFAULT (the first declared when none is).
const Profile& default_profile();
// Adds --profile to a subcommand (default: default_profile(); one of profiles() or `list`).
void add_profile_option(CLI::App* sub, std::string& name);
// The table `--profile list` prints: name, controller, requirements, MCU.
void print_profiles();

}  // namespace ap::cli
