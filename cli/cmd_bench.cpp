// axisproof bench: builds the release preset's benchmarks (target `benchmarks`) and runs every Google Benchmark registered
// with ap_add_bench(); prints each benchmark's rate (items per second) as reported.
#include "cli.hpp"

#include <cstdio>
#include <fstream>
#include <string>

namespace ap::cli {

void add_bench(CLI::App& app) {
  auto* sub = app.add_subcommand("bench", "Build the release benchmarks and run them (rates, not timings)");
  static std::string filter;
  sub->add_option("--filter", filter, "Only benchmarks matching this regex");
  sub->final_callback([] {
    if (!ensure_built("release", {"benchmarks"}, true)) {
      std::fprintf(stderr, "axisproof bench: release build failed\n");
      exit_status() = 1;
      return;
    }
    std::ifstream list(build_dir("release") + "/benchmarks.txt");
    std::string exe;
    int count = 0;
    int matched = 0;
    int failed = 0;
    while (std::getline(list, exe)) {
      if (exe.empty()) continue;
      ++count;
      std::string sel = filter.empty() ? "" : " --benchmark_filter=" + quote(filter);
      // A filter that matches nothing in this binary is not a failure of the binary; one
      // that matches nothing anywhere is a usage error (a typo must not pass as a run).
      if (!filter.empty()) {
        int st = 0;
        const std::string names = run_capture(quote(exe) + " --benchmark_list_tests=true" + sel + " 2>/dev/null", &st);
        if (st != 0 || names.find_first_not_of(" \n") == std::string::npos) continue;
      }
      ++matched;
      if (run(quote(exe) + " --benchmark_counters_tabular=true" + sel) != 0) ++failed;
    }
    if (count == 0) {
      std::fprintf(stderr, "axisproof bench: no benchmarks are registered yet\n");
      exit_status() = 1;
      return;
    }
    if (matched == 0) {
      std::fprintf(stderr, "axisproof bench: no benchmark matches --filter '%s'\n", filter.c_str());
      exit_status() = 2;
      return;
    }
    exit_status() = failed == 0 ? 0 : 1;
  });
}

}  // namespace ap::cli
