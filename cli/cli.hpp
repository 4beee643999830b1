#pragma once
// Shared plumbing of the axisproof subcommands: where the tree is, how to run a
// process, how to make sure a preset is built. Each subcommand lives in cmd_<name>.cpp
// and registers itself through one add_<name>() function listed in main.cpp.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ap::cli {

// Exit status the chosen subcommand wants; set from its callback.
int& exit_status();
// Set by Ctrl-C or SIGTERM while `axisproof panel` serves (cmd_panel.cpp).
bool panel_stop_requested();

std::string source_dir();
std::string build_dir(const std::string& preset);

// Runs a shell command line; returns its exit status (127 when it could not start).
int run(const std::string& command_line);
// Runs and captures stdout; exit status in *status.
std::string run_capture(const std::string& command_line, int* status);
std::string quote(const std::string& s);
// A string's bytes, for the codecs' span interfaces.
inline std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Configures the preset if its build tree does not exist yet, then builds it
// incrementally (optionally only some targets). Returns true on success.
bool ensure_built(const std::string& preset, const std::vector<std::string>& targets = {},
                  bool quiet = false);

double seconds_since(std::chrono::steady_clock::time_point start);

void add_test(CLI::App& app);
void add_gate(CLI::App& app);
void add_prove(CLI::App& app);
void add_fuzz(CLI::App& app);
void add_sim(CLI::App& app);
void add_bench(CLI::App& app);
void add_frame(CLI::App& app);
void add_panel(CLI::App& app);

}  // namespace ap::cli
