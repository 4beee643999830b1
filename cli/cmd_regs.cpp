// axisproof regs: placeholder until issue 4 lands; it says so and fails, never pretends.
#include "cli.hpp"

#include <cstdio>

namespace ap::cli {

void add_regs(CLI::App& app) {
  auto* sub = app.add_subcommand("regs", "Print the TMC2130 register map and decode datagrams");
  sub->final_callback([] {
    std::fprintf(stderr, "axisproof regs: not available yet (issue 4)\n");
    exit_status() = 1;
  });
}

}  // namespace ap::cli
