// axisproof bench: builds the release preset and runs every Google Benchmark registered
// with ap_add_bench(); prints each benchmark's rate (items per second) as reported.
#include "cli.hpp"

#include <cstdio>
#include <fstream>
#include <string>

namespace ap::cli {

void add_bench(CLI::App& app) {
  auto* sub = app.add_subcommand("bench", "Build the release preset and run the benchmarks (rates, not timings)");
  static std::string filter;
  sub->add_option("--filter", filter, "Only benchmarks matching this regex");
  sub->final_callback([] {
    if (!ensure_built("release", {}, true)) {
      std::fprintf(stderr, "axisproof bench: release build failed\n");
      exit_status() = 1;
      return;
    }
    std::ifstream list(build_dir("release") + "/benchmarks.txt");
    std::string exe;
    int count = 0;
    int failed = 0;
    while (std::getline(list, exe)) {
      if (exe.empty()) continue;
      ++count;
      std::string cmd = quote(exe) + " --benchmark_counters_tabular=true";
      if (!filter.empty()) cmd += " --benchmark_filter=" + quote(filter);
      if (run(cmd) != 0) ++failed;
    }
    if (count == 0) {
      std::fprintf(stderr, "axisproof bench: no benchmarks are registered yet\n");
      exit_status() = 1;
      return;
    }
    exit_status() = failed == 0 ? 0 : 1;
  });
}

}  // namespace ap::cli
