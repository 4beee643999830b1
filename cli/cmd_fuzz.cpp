// axisproof fuzz: placeholder until issue 8 lands; it says so and fails, never pretends.
#include "cli.hpp"

#include <cstdio>

namespace ap::cli {

void add_fuzz(CLI::App& app) {
  auto* sub = app.add_subcommand("fuzz", "Run the libFuzzer targets and merge their corpora");
  sub->final_callback([] {
    std::fprintf(stderr, "axisproof fuzz: not available yet (issue 8)\n");
    exit_status() = 1;
  });
}

}  // namespace ap::cli
