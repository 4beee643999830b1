// The release gate's release stages: the mutation suite, coverage, the Cortex-M4 build and its
// size table, the image under QEMU and the benchmark smoke. Split out of cmd_gate.cpp to keep
// each file of the gate readable; the stages are described in docs/architecture.md, "The
// release gate", and docs/qemu.md (see gate_stages.hpp).
#include "cli.hpp"
#include "gate_shard.hpp"
#include "gate_stages.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli::gate_stages {
namespace {

constexpr double kMinBranchCoverage = 90.0;

std::map<std::string, std::string> read_kv(const std::string& path) {
  std::map<std::string, std::string> kv;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return kv;
}

}  // namespace

Outcome m4_build(gate::Run& run, const std::string& log);
Outcome bench_run(const std::string& log);

Outcome mutation_stage(gate::Run& run, const std::string& log) {
  // The runner picks a profile's mutants by their Profile: header; asked first for the
  // profile's own, so a profile without any is NOT RUN rather than judged on the harness's.
  int listed = 0;
  const std::string own = run_capture("cd " + quote(source_dir()) + " && ci/mutate --list --profile " +
                                          std::string(g_profile->name) + " 2>/dev/null",
                                      &listed);
  if (listed != 0 || trim(own).empty()) return {Result::NotRun, "no mutants of this profile in ci/mutants/"};
  const auto own_and_harness = [] {
    int st = 0;
    return run_capture("cd " + quote(source_dir()) + " && ci/mutate --list --profile " + std::string(g_profile->name) +
                           ",harness 2>/dev/null",
                       &st);
  };
  std::error_code ec;
  fs::remove(source_dir() + "/out/mutate/report.tsv", ec);
  // The runner judges each mutant in build/asan only (overlay mode, ci/mutate --builds asan):
  // with lld the asan build relinks and checks a mutant as fast as the gcc one, and judging
  // there spares the gate a second full build (docs/architecture.md). When the earlier test,
  // proofs, fuzz and e2e stages all passed in that same build, they ran every test a Killed-by
  // ctest check can select, and the wider stages (ctest labels and `axisproof prove`), so only
  // the other Killed-by checks (`axisproof` commands) get a baseline run; otherwise the runner
  // runs the whole baseline, and leaves out any wider stage that fails on the unmutated tree.
  if (!built_ok["dev"] || !built_ok["asan"]) return {Result::NotRun, "build (dev) or build (asan) failed"};
  bool earlier_pass = true;
  for (const auto& r : run.rows) {
    if ((r.stage == "unit/property/proof tests" || r.stage == "proofs" || r.stage == "fuzz smoke" ||
         r.stage == "end-to-end scenarios") &&
        r.outcome.result != Result::Pass) {
      earlier_pass = false;
    }
  }
  // The profile's mutants and the harness's own (README, bootstrap, CLI), like the tests. A
  // shard judges its own, named. Its earlier stages ran only its own tests, so the baseline
  // they stand for is the union of the shards' test stages: the join's verdict is PASS only
  // when every shard's test stages passed on this commit (docs/ci.md "Shards").
  std::vector<std::string> all;
  {
    std::istringstream in(own_and_harness());
    std::string l;
    while (std::getline(in, l)) {
      std::istringstream row(l);
      std::string name;
      if (row >> name) all.push_back(name);
    }
  }
  const std::vector<std::string> mine = my_parts("mutation", all);
  if (mine.empty()) return {Result::Pass, "0 of " + std::to_string(all.size()) + " mutants in shard " + shard_text()};
  std::string which = " --profile " + std::string(g_profile->name) + ",harness";
  if (g_shard.on()) {
    which.clear();
    for (const auto& n : mine) which += " " + quote(n);
  }
  const int st = run_logged("ci/mutate --builds asan --jobs " + std::to_string(build_jobs()) +
                                (earlier_pass ? " --no-wide-baseline --no-ctest-baseline" : "") + which,
                            log,
                            R"(^\[\d+/\d+\]|^mutate: )");
  std::ifstream tsv(source_dir() + "/out/mutate/report.tsv");
  std::string line;
  std::getline(tsv, line);  // header
  int killed = 0, total = 0;
  std::vector<std::string> bad;
  while (std::getline(tsv, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string part;
    while (std::getline(ss, part, '\t')) f.push_back(part);
    if (f.size() < 4) continue;
    run.details.mutants.push_back(f);
    double secs = 0;
    try {
      secs = std::stod(f[3]);
    } catch (...) {
    }
    run.items["mutation"].push_back({f[0], f[2], f[2].rfind("killed", 0) == 0, secs});
    ++total;
    if (f[2].rfind("killed", 0) == 0) ++killed;
    else bad.push_back(f[0] + " " + (f[2] == "SURVIVED" ? "SURVIVED" : "INVALID"));
  }
  const std::string text = slurp(log);
  std::smatch m;
  if (std::regex_search(text, m, std::regex(R"(mutation suite: ([^\n]*))"))) run.details.mutation_summary = m[1].str();
  if (total == 0) return {Result::Fail, "runner failed before any mutant (baseline or build; see log)"};
  std::string key = std::to_string(killed) + "/" + std::to_string(total) + " killed" +
                    (g_shard.on() ? " (of " + std::to_string(all.size()) + ", shard " + shard_text() + ")" : "");
  for (size_t i = 0; i < bad.size() && i < 3; ++i) key += (i ? ", " : "; ") + bad[i];
  if (bad.size() > 3) key += ", ...";
  if (total != static_cast<int>(mine.size())) {
    return {Result::Fail, key + "; the runner judged " + std::to_string(total) + " of the " + std::to_string(mine.size()) + " mutants asked"};
  }
  return {st == 0 && killed == total ? Result::Pass : Result::Fail, key};
}

// A shard's tests wrote only part of the profiles: it keeps them, merged, for the join, which
// measures the coverage of all shards' profiles together (gate_join.cpp).
Outcome keep_profiles_for_join(const std::string& log) {
  if (!asan_shared() || !fs::is_directory(profile_dir()) || fs::is_empty(profile_dir())) {
    return {Result::NotRun, "no coverage profiles from this shard's tests (build/asan without AP_COVERAGE?)"};
  }
  const std::string out = gate_dir() + "/coverage.profdata";
  const int st = run_logged("$(command -v llvm-profdata-14 || command -v llvm-profdata) merge -sparse " + quote(profile_dir()) +
                                "/*.profraw -o " + quote(out),
                            log);
  if (st != 0) return {Result::Fail, "llvm-profdata merge of this shard's profiles failed (see log)"};
  return {Result::Pass, "this shard's profiles merged into coverage.profdata; the join measures all shards' together"};
}

Outcome coverage_stage(gate::Run& run, const std::string& log) {
  if (g_shard.on()) return keep_profiles_for_join(log);
  return coverage_report(run, log, profile_dir());
}

Outcome coverage_report(gate::Run& run, const std::string& log, const std::string& profiles) {
  char thr[16];
  std::snprintf(thr, sizeof thr, "%.0f", kMinBranchCoverage);
  // The test stages of the asan build wrote the profiles; without them (an asan build without
  // coverage), ci/coverage builds the cov preset and runs the suite again.
  const bool shared = asan_shared() && fs::is_directory(profiles) && !fs::is_empty(profiles);
  const std::string from = shared ? " --build-dir " + quote(build_dir("asan")) + " --profiles " + quote(profiles) : "";
  std::string sources;
  std::string measured;
  for (const auto& p : g_profile->coverage_paths) {
    sources += " --source " + quote(std::string(p));
    measured += (measured.empty() ? "" : ", ") + std::string(p);
  }
  const int st = run_logged("ci/coverage tests" + from + sources + " --min-branch " + std::string(thr), log, R"(^coverage)");
  const auto kv = read_kv(source_dir() + "/out/coverage/tests/summary.txt");
  if (kv.count("branch_percent") == 0) return {Result::Fail, "no coverage figures (see log)"};
  const std::string key = "branch " + kv.at("branch_percent") + " % (min " + thr + " %), line " + kv.at("line_percent") +
                          " %, " + kv.at("files") + " files of " + measured;
  run.details.coverage_summary = "The profile's declared code folders (its core, protocol and PC folders and the shared folders it uses: " +
                                 measured + ") from the whole test suite (" + std::string(shared ? "asan build, the gate's test stages" : "cov preset") + "): lines " + kv.at("line_percent") +
                                 " % of " + kv.at("lines") + ", branches " + kv.at("branch_percent") + " % of " +
                                 kv.at("branches") + "; the gate requires at least " + thr + " % branch coverage.";
  std::ifstream rep(source_dir() + "/out/coverage/tests/report.txt");
  std::string line;
  const std::string src = source_dir() + "/";
  while (std::getline(rep, line)) {
    std::istringstream row(line);
    std::vector<std::string> f;
    std::string w;
    while (row >> w) f.push_back(w);
    if (f.size() != 13 || f[0] == "Filename") continue;
    std::string file = f[0];
    if (file.rfind(src, 0) == 0) file = file.substr(src.size());
    run.details.coverage.push_back({file, f[7], f[9], f[10], f[12]});
  }
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

Outcome m4_stage(gate::Run& run, const std::string& log) {
  if (!my_part("m4", "m4")) {
    // Another shard's stage; this one builds the image only when it has QEMU scenarios to boot.
    const std::string owner = "shard " + std::to_string(shard_of("m4", "m4")) + "/" + std::to_string(g_shard.count);
    bool boots = false;
    for (const auto& n : g_profile->qemu_scenarios) boots = boots || my_part("qemu", std::string(n));
    boots = boots || my_part("qemu", "repeat:" + repeat_scenario());
    if (!boots || g_profile->qemu_scenarios.empty()) return {Result::Pass, "in " + owner};
    const int st = run_logged("ci/m4-build --profile " + std::string(g_profile->name) + " --out " + quote(gate_dir() + "/m4-for-qemu"), log,
                              R"(m4-build:)");
    return {st == 0 ? Result::Pass : Result::Fail,
            std::string(st == 0 ? "built" : "build failed") + " for this shard's QEMU scenarios; the stage is " + owner + "'s"};
  }
  const auto t0 = std::chrono::steady_clock::now();
  const Outcome o = m4_build(run, log);
  run.items["m4"].push_back({"m4", gate::to_string(o.result), o.result == Result::Pass, seconds_since(t0)});
  return o;
}

Outcome m4_build(gate::Run& run, const std::string& log) {
  const int st = run_logged("ci/m4-build --profile " + std::string(g_profile->name) + " --out " + quote(release_dir()), log,
                            R"(^total|^flash|m4-build:)");
  const std::string table = release_dir() + "/" + std::string(g_profile->size_tag) + "-size";
  run.details.m4_size_md = slurp(table + ".md");
  const std::string txt = slurp(table + ".txt");
  std::smatch m;
  std::string key = st == 0 ? "built" : "cross build or check failed (see log)";
  if (std::regex_search(txt, m, std::regex(R"(flash (\d+) B of (\d+) B \(([\d.]+)%\), RAM (\d+) B of (\d+) B \(([\d.]+)%\))"))) {
    const auto kb = [](const std::string& b) {
      const long long n = std::stoll(b);
      return n % 1024 == 0 ? std::to_string(n / 1024) + " KB" : std::to_string(n) + " B";
    };
    key = "flash " + m[1].str() + " B (" + m[3].str() + " % of " + kb(m[2].str()) + "), RAM " + m[4].str() + " B (" + m[6].str() +
          " % of " + kb(m[5].str()) + ")";
    if (st != 0) key += "; check failed";
  }
  // The board's linked image (docs/qemu.md), where the profile has one.
  if (std::regex_search(txt, m, std::regex(R"((ap_\w+_l476\.elf)\s+flash\s+(\d+) B\s+RAM\s+(\d+) B \(stack (\d+) B\))"))) {
    key += "; " + m[1].str() + " linked: flash " + m[2].str() + " B, RAM " + m[3].str() + " B (stack " + m[4].str() + " B)";
  }
  const std::string text = slurp(log);
  if (text.find("no core libraries are defined yet") != std::string::npos) return {Result::NotRun, "no core libraries yet"};
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

// The bootable image in the loop (docs/qemu.md "The gate stage"): each of the profile's QEMU
// scenarios runs on the image the m4 stage built from these sources, with the host core as its
// lockstep mirror (any difference in SPI traffic, motor outputs, TX bytes or axis positions is
// a violation), and again on the host simulator alone: the two trace.csv must be equal byte
// for byte. One scenario (the shortest by the recorded times, repeat_scenario()) runs on the
// image twice: the same scenario gives the same trace. Parts of the shard plan: each scenario
// by its name, and "repeat:NAME".
Outcome qemu_stage(gate::Run& run, const std::string& log) {
  const bool m4_ok = std::any_of(run.rows.begin(), run.rows.end(), [](const gate::Row& r) {
    return r.stage == "cortex-m4 build" && r.outcome.result == Result::Pass;
  });
  if (!m4_ok) return {Result::NotRun, "the cortex-m4 build did not pass: no image"};
  const std::string root = gate_dir() + "/qemu";
  const std::string self = quote(self_exe());
  const std::string profile = std::string(g_profile->name);
  const auto stats = [](const std::string& file) {
    std::map<std::string, std::string> kv;
    std::ifstream in(file);
    std::string k, v;
    while (in >> k >> v) kv[k] = v;
    return kv;
  };
  const auto scn = [](const std::string& name) { return quote(scenarios_dir(*g_profile) + "/" + name + ".scn"); };
  std::vector<std::string> names;
  for (const auto& n : g_profile->qemu_scenarios) {
    if (my_part("qemu", std::string(n))) names.push_back(std::string(n));
  }
  const std::string again_name = repeat_scenario();
  const bool repeat = !again_name.empty() && my_part("qemu", "repeat:" + again_name);
  if (names.empty() && !repeat) return {Result::Pass, "0 of " + std::to_string(g_profile->qemu_scenarios.size()) + " scenarios in shard " + shard_text()};
  int passed = 0;
  double emulated = 0, wall = 0;
  unsigned long stack = 0, stack_size = 0;
  std::vector<std::string> bad;
  // Two scenarios at once (run_parallel): each run is one emulator and one mirror process
  // taking turns, about one core. Each writes its own log, appended to the stage's in order.
  std::vector<int> host_st(names.size(), 0), image_st(names.size(), 0);
  std::vector<double> secs(names.size(), 0.0);
  run_parallel(names.size(), [&](std::size_t i) {
    const std::string& name = names[i];
    const std::string own = root + "/logs/" + name + ".log";
    std::error_code rm_ec;
    fs::remove(own, rm_ec);
    const auto t0 = std::chrono::steady_clock::now();
    host_st[i] = run_logged(self + " sim run --profile " + profile + " " + scn(name) + " --out " + quote(root + "/host"), own);
    image_st[i] = run_logged(self + " sim run --profile " + profile + " " + scn(name) + " --target qemu --out " + quote(root + "/qemu"), own,
                             "^scenario ");
    secs[i] = seconds_since(t0);
  });
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const int host = host_st[i];
    const int image = image_st[i];
    {
      std::ofstream out(log, std::ios::app);
      out << slurp(root + "/logs/" + name + ".log");
    }
    const auto kv = stats(root + "/qemu/" + name + "/qemu.txt");
    const bool same = slurp(root + "/host/" + name + "/trace.csv") == slurp(root + "/qemu/" + name + "/trace.csv") &&
                      !slurp(root + "/qemu/" + name + "/trace.csv").empty();
    if (kv.count("ticks") != 0) {
      emulated += std::stod(kv.at("emulated_s"));
      wall += std::stod(kv.at("wall_s"));
      stack = std::max(stack, std::stoul(kv.at("stack_used")));
      stack_size = std::stoul(kv.at("stack_size"));
    }
    const bool ok = host == 0 && image == 0 && same;
    const std::string verdict = ok ? "passed" : image != 0 ? "FAIL on the image" : host != 0 ? "FAIL on the host" : "traces differ";
    run.items["qemu"].push_back({name, verdict, ok, secs[i]});
    if (ok) ++passed;
    else bad.push_back(name + " " + verdict);
  }
  bool repeatable = false;
  if (repeat) {
    // Its first image run is this shard's own, or one more run when another shard has the scenario.
    const auto t0 = std::chrono::steady_clock::now();
    std::string first = root + "/qemu/" + again_name + "/trace.csv";
    int st = 0;
    if (std::find(names.begin(), names.end(), again_name) == names.end()) {
      st = run_logged(self + " sim run --profile " + profile + " " + scn(again_name) + " --target qemu --out " + quote(root + "/first"), log);
      first = root + "/first/" + again_name + "/trace.csv";
    }
    const int again = run_logged(self + " sim run --profile " + profile + " " + scn(again_name) + " --target qemu --out " + quote(root + "/again"), log);
    repeatable = st == 0 && again == 0 && !slurp(first).empty() && slurp(root + "/again/" + again_name + "/trace.csv") == slurp(first);
    if (!repeatable) bad.push_back(again_name + " gave another trace the second time");
    run.items["qemu"].push_back({"repeat:" + again_name, repeatable ? "same trace" : "another trace", repeatable, seconds_since(t0)});
  }
  const std::size_t n = g_profile->qemu_scenarios.size();
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%d/%zu scenarios PASS on the image%s, traces equal to the host's%s; emulated %.1f s in %.1f s wall (%.2fx, "
                "two runs at once); "
                "stack high-water %lu of %lu B",
                passed, g_shard.on() ? names.size() : n, g_shard.on() ? (" (of " + std::to_string(n) + ", shard " + shard_text() + ")").c_str() : "",
                repeat ? (", " + again_name + (repeatable ? " repeatable" : " NOT repeatable")).c_str() : "", emulated, wall, wall > 0 ? emulated / wall : 0.0, stack, stack_size);
  std::string key = buf;
  for (std::size_t i = 0; i < bad.size() && i < 3; ++i) key += (i ? ", " : "; ") + bad[i];
  const bool all_passed = passed == static_cast<int>(names.size());
  return {all_passed && (repeatable || !repeat) && n > 0 ? Result::Pass : Result::Fail, key};
}

// The README's `axisproof bench` end to end (release benchmarks build, one benchmark runs): a
// smoke of the command, not a performance check, so the rate is reported and never judged.
Outcome bench_stage(gate::Run& run, const std::string& log) {
  if (!my_part("bench", "bench")) return {Result::Pass, "in shard " + std::to_string(shard_of("bench", "bench")) + "/" + std::to_string(g_shard.count)};
  const auto t0 = std::chrono::steady_clock::now();
  const Outcome o = bench_run(log);
  run.items["bench"].push_back({"bench", gate::to_string(o.result), o.result == Result::Pass, seconds_since(t0)});
  return o;
}

Outcome bench_run(const std::string& log) {
  const char* kBenchmark = "BM_ProtocolParseCommand";
  const int st = run_logged(quote(self_exe()) + " bench --filter '^" + kBenchmark + "$'", log, std::string("^") + kBenchmark);
  std::smatch m;
  const std::string text = slurp(log);
  std::string key = st == 0 ? "ran" : "bench failed (see log)";
  if (std::regex_search(text, m, std::regex(std::string(kBenchmark) + R"(\s+\S+ ns\s+\S+ ns\s+\d+\s+(\S+/s))")))
    key = std::string(kBenchmark) + " " + m[1].str() + " (CPU time, release build)";
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

}  // namespace ap::cli::gate_stages
