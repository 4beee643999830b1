#pragma once
// The XY profile's own subcommands (its entry's add_commands, cli/profile.hpp).
#include <CLI/CLI.hpp>

#include <string>

#include "profile.hpp"

namespace ap::cli {

// axisproof regs: the TMC2130 register map and a decoder for captured datagrams.
void add_regs(CLI::App& app);
// axisproof gcode: a G-code program planned, sent over the simulated link and drawn.
void add_gcode(CLI::App& app);
// The XY board's QEMU image (docs/qemu.md), built in the m4 tree first if needed.
std::string xy_qemu_image();
// axisproof panel --profile xy (docs/panel.md).
int xy_panel(const PanelArgs& a);

}  // namespace ap::cli
