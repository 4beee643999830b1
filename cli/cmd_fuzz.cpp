// axisproof fuzz: builds the fuzz preset (clang, libFuzzer + ASan + UBSan) and runs each
// libFuzzer target in fork mode (crash-, timeout- and OOM-resistant) for a time budget with a
// progress line, using fuzz/<profile>/dict/<target or group>.dict when present. Afterwards:
//   - new inputs are merged into fuzz/<profile>/corpus/<target> with -merge=1 (only inputs that add
//     coverage are kept);
//   - each distinct finding (crash, leak, timeout, OOM; distinct = sanitizer summary plus the
//     top project frames) is minimised with -minimize_crash and written to
//     fuzz/<profile>/regressions/<target>/<kind>-<sha1> with a one-line <kind>-<sha1>.txt summary; the
//     replay ctest (label fuzz) then replays it in every preset;
//   - out/fuzz/<target>/stats.txt records executions, exec/s, corpus size, coverage, findings.
// Exit 1 when anything was found (or could not run), 0 otherwise; usage errors exit 2.
// One target's run (fuzzing, merge, minimisation) is in fuzz_run.cpp; this file reads
// fuzz_targets.txt, builds the targets, runs them in turn and holds the command.
#include "cli.hpp"
#include "fuzz_run.hpp"
#include "profile.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli {

std::vector<FuzzTarget> read_fuzz_targets(const std::string& build, std::string_view profile) {
  std::vector<FuzzTarget> out;
  std::ifstream in(build + "/fuzz_targets.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string part;
    while (std::getline(ss, part, '\t')) f.push_back(part);
    if (f.size() < 6 || f[4] != profile) continue;
    out.push_back({f[0], f[1], f[2], f[3], f[4], f[5]});
  }
  return out;
}

namespace {

void write_stats(const fs::path& file, const FuzzStats& s) {
  std::ofstream out(file);
  out << "target=" << s.target << "\nexecutions=" << s.executions << "\nexec_per_s=" << s.exec_per_s
      << "\ncorpus_files=" << s.corpus_files << "\ncoverage=" << s.coverage << "\nnew_inputs=" << s.new_inputs
      << "\nfindings=" << s.findings << "\nnew_findings=" << s.new_findings << "\nseconds=" << s.seconds
      << "\nnote=" << s.note << "\n";
}

}  // namespace

namespace {
// --build-dir (or AP_FUZZ_BUILD_DIR): a fuzz-preset build tree other than build/fuzz, e.g. one
// engineer's own while others share the checkout. Empty: build/fuzz.
std::string g_build_dir;

std::string fuzz_build_dir() {
  std::string d = g_build_dir;
  if (d.empty()) {
    const char* env = std::getenv("AP_FUZZ_BUILD_DIR");
    if (env != nullptr) d = env;
  }
  if (d.empty()) return build_dir("fuzz");
  return fs::absolute(fs::path(d)).lexically_normal().string();
}

bool build_fuzz_targets(const std::string& build, const std::vector<std::string>& names) {
  if (build == build_dir("fuzz")) return ensure_built("fuzz", names, true);
  std::string cmd = "cmake --build " + quote(build) + " --target";
  for (const auto& n : names) cmd += " " + n;
  int status = 0;
  const std::string out = run_capture(cmd + " 2>&1", &status);
  if (status != 0) std::fputs(out.c_str(), stderr);
  return status == 0;
}
}  // namespace

std::vector<FuzzStats> run_fuzz(const FuzzOptions& o, bool* ok) {
  *ok = true;
  std::vector<FuzzStats> results;
  const std::string build = fuzz_build_dir();
  if (!fs::exists(build + "/CMakeCache.txt")) {
    std::fprintf(stderr, "axisproof: configuring %s\n", build.c_str());
    int status = 0;
    const std::string out =
        run_capture("cd " + quote(source_dir()) + " && cmake --preset fuzz -B " + quote(build) + " 2>&1", &status);
    if (status != 0) {
      std::fputs(out.c_str(), stderr);
      std::fprintf(stderr, "axisproof fuzz: configuring the fuzz preset failed\n");
      *ok = false;
      return results;
    }
  }
  const std::vector<FuzzTarget> mine = read_fuzz_targets(build, o.profile);
  std::vector<FuzzTarget> chosen;
  if (o.targets.empty()) {
    chosen = mine;
  } else {
    for (const auto& name : o.targets) {
      auto it = std::find_if(mine.begin(), mine.end(), [&](const FuzzTarget& t) { return t.name == name; });
      if (it == mine.end()) {
        std::fprintf(stderr, "axisproof fuzz: profile %s has no fuzz target named '%s'", o.profile.c_str(), name.c_str());
        for (size_t i = 0; i < mine.size(); ++i) std::fprintf(stderr, "%s%s", i ? ", " : " (have: ", mine[i].name.c_str());
        std::fprintf(stderr, "%s\n", mine.empty() ? "" : ")");
        *ok = false;
        return results;
      }
      chosen.push_back(*it);
    }
  }
  if (chosen.empty()) {
    std::fprintf(stderr, "axisproof fuzz: profile %s has no fuzz targets (fuzz/<profile>/... with ap_add_fuzz_target)\n",
                 o.profile.c_str());
    *ok = false;
    return results;
  }
  std::vector<std::string> names;
  for (const auto& t : chosen) names.push_back("fuzz_" + t.name);
  if (!build_fuzz_targets(build, names)) {
    std::fprintf(stderr, "axisproof fuzz: building the fuzz preset failed\n");
    *ok = false;
    return results;
  }
  const std::vector<FuzzTarget> all = read_fuzz_targets(build, o.profile);  // the build may have re-run CMake
  for (const auto& c : chosen) {
    auto it = std::find_if(all.begin(), all.end(), [&](const FuzzTarget& t) { return t.name == c.name; });
    FuzzStats st = it == all.end() ? FuzzStats{} : fuzz_engine::fuzz_one(*it, o);
    if (it == all.end()) {
      st.target = c.name;
      st.note = "target disappeared from the build";
    }
    fs::create_directories(source_dir() + "/out/fuzz/" + c.name);
    write_stats(source_dir() + "/out/fuzz/" + c.name + "/stats.txt", st);
    if (!st.ran) *ok = false;
    results.push_back(st);
  }
  return results;
}

void add_fuzz(CLI::App& app) {
  auto* sub = app.add_subcommand("fuzz", "Run the libFuzzer targets (fork mode), merge their corpora, minimise findings into fuzz/<profile>/regressions");
  static std::vector<std::string> targets;
  static bool all = false;
  static FuzzOptions opts;
  auto* t = sub->add_option("-t,--target", targets, "Fuzz target to run (repeatable); see build/fuzz/fuzz_targets.txt");
  sub->add_flag("-a,--all", all, "Run every fuzz target of the profile")->excludes(t);
  sub->add_option("--build-dir", g_build_dir,
                  "Fuzz-preset build tree to use (default build/fuzz, or $AP_FUZZ_BUILD_DIR); configured with --preset fuzz if new");
  sub->add_option("--time", opts.seconds, "Seconds per target (default 60)")->check(CLI::PositiveNumber);
  sub->add_option("-j,--jobs", opts.jobs, "Parallel fuzzing processes (libFuzzer -fork=N, default 2)")->check(CLI::Range(1, 64));
  add_profile_option(sub, opts.profile);
  sub->add_flag("--no-save", opts.no_save,
                "Leave the corpora and regressions (fuzz/<profile>/) untouched: merged corpus and reproducers stay under out/fuzz/<target>/");
  sub->final_callback([] {
    if (targets.empty() && !all) {
      std::fprintf(stderr, "axisproof fuzz: name a target with --target T or use --all (see axisproof fuzz --help)\n");
      exit_status() = 2;
      return;
    }
    opts.targets = targets;
    bool ok = true;
    const auto results = run_fuzz(opts, &ok);
    if (!results.empty()) {
      std::printf("\n%-24s %12s %9s %8s %6s %9s %9s\n", "target", "executions", "exec/s", "corpus", "cov", "new-in", "findings");
      for (const auto& r : results) {
        std::printf("%-24s %12lld %9lld %8lld %6lld %9d %9d%s%s\n", r.target.c_str(), r.executions, r.exec_per_s,
                    r.corpus_files, r.coverage, r.new_inputs, r.findings, r.note.empty() ? "" : "  ", r.note.c_str());
      }
    }
    int findings = 0;
    for (const auto& r : results) findings += r.findings;
    if (findings > 0) {
      std::printf("\naxisproof fuzz: %d finding(s); reproducers in %s\n", findings,
                  opts.no_save ? "out/fuzz/<target>/findings/" : "fuzz/<profile>/regressions/<target>/");
    }
    exit_status() = ok && findings == 0 ? 0 : 1;
  });
}

}  // namespace ap::cli
