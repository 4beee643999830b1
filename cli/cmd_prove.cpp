// axisproof prove: placeholder until issue 7 lands; it says so and fails, never pretends.
#include "cli.hpp"

#include <cstdio>

namespace ap::cli {

void add_prove(CLI::App& app) {
  auto* sub = app.add_subcommand("prove", "Prove the safety obligations with Z3");
  sub->final_callback([] {
    std::fprintf(stderr, "axisproof prove: not available yet (issue 7)\n");
    exit_status() = 1;
  });
}

}  // namespace ap::cli
