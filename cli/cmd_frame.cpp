// axisproof frame: placeholder until issue 3 lands; it says so and fails, never pretends.
#include "cli.hpp"

#include <cstdio>

namespace ap::cli {

void add_frame(CLI::App& app) {
  auto* sub = app.add_subcommand("frame", "Encode and decode protocol frames");
  sub->final_callback([] {
    std::fprintf(stderr, "axisproof frame: not available yet (issue 3)\n");
    exit_status() = 1;
  });
}

}  // namespace ap::cli
