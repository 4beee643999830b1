// axisproof sim: placeholder until issue 9 lands; it says so and fails, never pretends.
#include "cli.hpp"

#include <cstdio>

namespace ap::cli {

void add_sim(CLI::App& app) {
  auto* sub = app.add_subcommand("sim", "Run the simulated PC and board over the DDS test bus");
  sub->final_callback([] {
    std::fprintf(stderr, "axisproof sim: not available yet (issue 9)\n");
    exit_status() = 1;
  });
}

}  // namespace ap::cli
