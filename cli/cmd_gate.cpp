// axisproof gate: the release gate. Runs each stage in order with a progress display, prints
// a verdict table (stage, result, time, key figure) and exits 0 only when every stage PASSed.
// A stage that could not run is NOT RUN, and NOT RUN fails the gate: a gate that skips
// silently would pass firmware nobody checked. `--skip STAGE` only marks a stage NOT RUN.
//
// Builds are shared so the gate fits in 20 minutes on a 2-core machine: one full build (asan)
// serves every stage, and the dev build only gives the CLI the gate itself runs. The asan
// preset carries, besides ASan + UBSan, clang source-based coverage and the libFuzzer binaries
// (AP_COVERAGE, AP_FUZZ_BINARIES), so the test stages write the coverage profiles and the fuzz
// smoke runs that build's fuzz_<t>; the mutation runner reuses build/asan through an overlay
// (ci/mutate). docs/architecture.md, "The release gate".
//
// Stages (each one's output goes to out/gate/logs/<stage>.log):
//   build-dev    dev preset (gcc-12, -Werror): the CLI (axisproof target: every library of the
//                core, models, simulator and PC side it links), incrementally
//   build-asan   asan preset (clang, ASan + UBSan, coverage, fuzz binaries); re-configured
//                from the preset when an older build/asan lacks coverage or fuzz binaries
// Every stage judges one firmware profile (--profile P, default the one declared DEFAULT;
// docs/profiles.md): its tests and the harness's own (ctest -L '^(P|harness)$'), its fuzz
// targets, obligations, mutants, coverage folders and size check.
//   tests        ctest -L 'unit|property|proof' on the asan build (profiles to build/asan/profiles)
//   proofs       `axisproof prove` (NOT RUN while it is the placeholder)
//   fuzz         ctest -L fuzz on the asan build (replays corpora and regressions; not the
//                ClusterFuzzLite build-script check, which builds a tree of its own and runs in
//                `axisproof test`), then every fuzz_<t> of the asan build for --fuzz-time
//                seconds over a copy of its corpus (the tree is left untouched, new inputs and
//                findings go to out/gate/fuzz/<t>/)
//   e2e          ctest -L e2e on the asan build (NOT RUN when there are no e2e tests)
//   mutation     ci/mutate --profile P --builds asan: every mutant of the profile must be killed
//   coverage     ci/coverage tests over the profiles the test stages wrote (the asan build);
//                llvm-cov line + branch of the profile's coverage paths, FAIL below 90 % branch. Falls
//                back to the cov preset (a build of its own) when build/asan has no coverage.
//   m4           ci/m4-build: Cortex-M4 static libraries, the linked images, size table, symbol check
//   qemu         (profiles with a bootable image) the image under qemu-system-arm: its
//                scenarios PASS, their traces equal the host simulator's, and repeat
//   bench        `axisproof bench --filter` one benchmark: the README's bench command needs the
//                release preset, which `axisproof test` does not build, so the gate checks it
// Then out/gate/report.md + report.html, --junit FILE, and the release artifact under
// out/release/ (M4 libraries, size table, manifest.json / MANIFEST.md).
//
// The stages themselves are in gate_build_stages.cpp, gate_check_stages.cpp and
// gate_release_stages.cpp (gate_stages.hpp); this file keeps the command and the stage table.
#include "cli.hpp"
#include "gate.hpp"
#include "gate_shard.hpp"
#include "gate_stages.hpp"
#include "profile.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli {
namespace {

using gate::Outcome;
using gate::Result;

struct Stage {
  const char* id;    // for --skip
  const char* name;  // in the table
  std::function<Outcome(gate::Run&, std::string& log)> run;
};

std::string log_path(const char* id) { return gate_stages::gate_dir() + "/logs/" + id + ".log"; }

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace

void add_gate(CLI::App& app) {
  using namespace gate_stages;
  auto* sub = app.add_subcommand("gate", "Release gate on a profile's firmware core: every stage, a verdict table, exit 0 only on PASS");
  static std::string profile;
  add_profile_option(sub, profile);
  static std::string junit;
  static std::vector<std::string> skip;
  static std::string out_root;
  sub->add_option("--junit", junit, "Also write the verdict as JUnit XML to FILE");
  sub->add_option("--skip", skip, "Do not run STAGE (it is then NOT RUN, so the verdict is FAIL)")
      ->check(CLI::IsMember({"build-dev", "build-asan", "tests", "proofs", "fuzz", "e2e", "mutation", "coverage", "m4", "qemu", "bench"}));
  sub->add_option("--out", out_root, "Write the reports to DIR/gate and the release artifact to DIR/release (default out/)");
  sub->add_option("--fuzz-time", fuzz_seconds, "Seconds per fuzz target in the fuzz smoke stage (default 10)")
      ->check(CLI::PositiveNumber);
  static std::string shard;
  static std::string times;
  sub->add_option("--shard", shard,
                  "Run the I-th of N balanced parts of every stage that can be split (I/N, e.g. 2/4), after the same builds; "
                  "`axisproof gate join` merges the N results (docs/ci.md)");
  sub->add_option("--times", times,
                  "Balance the shards by the part times in FILE (default ci/gate-times/<profile>/times.tsv; every run writes "
                  "OUT/gate/times.tsv)");
  auto* join = add_gate_join(sub);
  sub->final_callback([join] {
    if (join->parsed()) return;  // `axisproof gate join` ran instead
    if (!shard.empty()) {
      std::string error;
      if (!parse_shard(shard, &g_shard, &error)) {
        std::fprintf(stderr, "axisproof gate: %s\n", error.c_str());
        exit_status() = 2;
        return;
      }
    }
    const std::string src = source_dir();
    std::error_code ec;
    g_out = out_root.empty() ? src + "/out" : fs::absolute(out_root).string();
    fs::remove_all(gate_dir(), ec);
    fs::remove_all(release_dir(), ec);
    fs::create_directories(gate_dir() + "/logs");
    g_profile = find_profile(profile);
    gate::Run run;
    run.profile = std::string(g_profile->name) + " (" + std::string(g_profile->title) + ")";
    run.size_tag = std::string(g_profile->size_tag);
    run.version = AP_VERSION;
    run.shard = shard_text();
    run.date = now_utc();
    int st = 0;
    run.git_hash = trim(run_capture("git -C " + quote(src) + " rev-parse HEAD 2>/dev/null", &st));
    if (run.git_hash.empty()) run.git_hash = "unknown";
    else if (!trim(run_capture("git -C " + quote(src) + " status --porcelain --untracked-files=no 2>/dev/null | head -1", &st)).empty())
      run.git_hash += " (with uncommitted changes)";

    const std::vector<Stage> stages = {
        // The dev build gives the CLI (the bootstrap built it; a no-op unless the sources
        // changed since). Its tests are not built: every test runs in the asan build, and
        // the mutants are judged there too (docs/architecture.md, "The release gate").
        {"build-dev", "build (dev)", [](gate::Run&, std::string& l) { return build_stage("dev", l, "axisproof"); }},
        {"build-asan", "build (asan)", [](gate::Run&, std::string& l) { return build_stage("asan", l); }},
        {"tests", "unit/property/proof tests",
         [](gate::Run& r, std::string& l) {
           std::error_code rm_ec;
           fs::remove_all(profile_dir(), rm_ec);  // the coverage stage reads what this and the later test stages write
           // The tests that prove the profile's whole obligation registry again (each module's
           // "every obligation is PROVED") are left to the proofs stage, which proves the same
           // list with the same solver and reports each obligation.
           return ctest_stage(r, "tests", "unit|property|proof", gate_dir() + "/junit-tests.xml", l,
                              std::string(g_profile->registry_tests));
         }},
        {"proofs", "proofs", [](gate::Run& r, std::string& l) { return proofs_stage(r, l); }},
        {"fuzz", "fuzz smoke", [](gate::Run& r, std::string& l) { return fuzz_stage(r, l); }},
        {"e2e", "end-to-end scenarios", [](gate::Run& r, std::string& l) { return e2e_stage(r, l); }},
        {"mutation", "mutation suite", [](gate::Run& r, std::string& l) { return mutation_stage(r, l); }},
        {"coverage", "coverage", [](gate::Run& r, std::string& l) { return coverage_stage(r, l); }},
        {"m4", "cortex-m4 build", [](gate::Run& r, std::string& l) { return m4_stage(r, l); }},
        {"bench", "benchmarks (release)", [](gate::Run& r, std::string& l) { return bench_stage(r, l); }},
    };
    // A profile with a bootable image also boots it (docs/qemu.md); the others have no such stage.
    std::vector<Stage> all = stages;
    if (!g_profile->qemu_scenarios.empty()) {
      all.insert(all.end() - 1, Stage{"qemu", "firmware (QEMU)", [](gate::Run& r, std::string& l) { return qemu_stage(r, l); }});
    }
    const auto start = std::chrono::steady_clock::now();
    run.pass = true;
    for (size_t i = 0; i < all.size(); ++i) {
      const auto& s = all[i];
      std::printf("[%zu/%zu] %s ...\n", i + 1, all.size(), s.name);
      std::fflush(stdout);
      const auto t0 = std::chrono::steady_clock::now();
      std::string log = log_path(s.id);
      Outcome o;
      if (std::find(skip.begin(), skip.end(), s.id) != skip.end()) {
        o = {Result::NotRun, "skipped with --skip " + std::string(s.id)};
        log.clear();
      } else {
        o = s.run(run, log);
      }
      const double secs = seconds_since(t0);
      std::string rel;
      if (!log.empty() && fs::exists(log)) rel = fs::relative(log, src).string();
      run.rows.push_back({s.id, s.name, o, secs, rel});
      // After the builds, the plan of the stages that can be split: every shard lists the same
      // parts from the same build and balances them by the same times file (gate_shard.hpp).
      if (std::string(s.id) == "build-asan" && o.result == Result::Pass) {
        const std::string from = times.empty() ? default_times_file() : fs::absolute(times).string();
        const std::string known = fs::exists(from) ? from : "";
        g_plan = make_plan(list_parts(known), parse_times(known.empty() ? std::string() : slurp(known)), g_shard.on() ? g_shard.count : 1);
        g_plan.times_file = known.empty() ? "" : fs::relative(known, src).string();
        if (g_shard.on()) {
          double mine = 0, total = 0;
          int n = 0;
          for (const auto& p : g_plan.parts) {
            total += p.seconds;
            if (p.shard == g_shard.index) {
              mine += p.seconds;
              ++n;
            }
          }
          std::printf("      shard %s: %d of %zu parts, %.0f of %.0f s by %s\n", shard_text().c_str(), n, g_plan.parts.size(), mine,
                      total, g_plan.times_file.empty() ? "no recorded times (1 s each)" : g_plan.times_file.c_str());
        }
      }
      std::printf("[%zu/%zu] %s: %s (%.1f s) %s\n", i + 1, all.size(), s.name, gate::to_string(o.result), secs, o.key.c_str());
      std::fflush(stdout);
      run.pass = run.pass && o.result == Result::Pass;
    }
    run.seconds = seconds_since(start);
    // SVG plots of the bundled scenarios, if `axisproof sim` left any: a profile's runs write
    // out/sim/<profile>/NAME/; only this profile's are shown.
    if (fs::is_directory(src + "/out/sim", ec)) {
      for (const auto& e : fs::recursive_directory_iterator(src + "/out/sim", ec)) {
        if (e.path().extension() != ".svg") continue;
        const std::string rel = fs::relative(e.path(), src + "/out/sim").string();
        const std::string top = rel.substr(0, rel.find('/'));
        if (find_profile(top) == g_profile) run.details.plots.push_back("../sim/" + rel);
      }
      std::sort(run.details.plots.begin(), run.details.plots.end());
    }
    time_tables(run, build_dir("asan"));
    gate::print_table(run);
    gate::write_reports(run, gate_dir());
    if (!g_shard.on()) gate::write_manifest(run, release_dir());  // a shard's release is the join's
    write_result(run, gate_dir() + "/result.json");
    write_times(run, gate_dir() + "/times.tsv");
    const std::string shown = out_root.empty() ? "out" : g_out;
    std::printf("report: %s/gate/report.md, %s/gate/report.html; release artifact: %s/release/\n", shown.c_str(), shown.c_str(),
                shown.c_str());
    if (!junit.empty()) {
      if (gate::write_junit(run, junit)) std::printf("JUnit XML: %s\n", junit.c_str());
      else std::fprintf(stderr, "axisproof gate: cannot write %s\n", junit.c_str());
    }
    exit_status() = run.pass ? 0 : 1;
  });
}

}  // namespace ap::cli
