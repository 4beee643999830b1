#pragma once
// The XY profile's own subcommands (its entry's add_commands, cli/profile.hpp).
#include <CLI/CLI.hpp>

namespace ap::cli {

// axisproof regs: the TMC2130 register map and a decoder for captured datagrams.
void add_regs(CLI::App& app);
// axisproof gcode: a G-code program planned, sent over the simulated link and drawn.
void add_gcode(CLI::App& app);

}  // namespace ap::cli
