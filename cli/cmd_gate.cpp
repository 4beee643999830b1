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
#include "cli.hpp"
#include "fuzz_run.hpp"
#include "gate.hpp"
#include "profile.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli {
namespace {

using gate::Outcome;
using gate::Result;

constexpr double kMinBranchCoverage = 90.0;

struct Stage {
  const char* id;    // for --skip
  const char* name;  // in the table
  std::function<Outcome(gate::Run&, std::string& log)> run;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
  size_t i = 0;
  while (i < s.size() && s[i] == ' ') ++i;
  return s.substr(i);
}

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

// Runs a shell command in the source dir, output (stdout + stderr) to `log`; lines matching
// `echo` are shown indented, as progress. Returns the exit status.
int run_logged(const std::string& command, const std::string& log, const std::string& echo = "") {
  fs::create_directories(fs::path(log).parent_path());
  std::ofstream out(log, std::ios::app);
  out << "$ " << command << "\n";
  out.flush();
  std::fflush(stdout);
  FILE* pipe = popen(("cd " + quote(source_dir()) + " && " + command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return 127;
  const std::regex re(echo.empty() ? "$^" : echo);
  char buf[8192];
  std::string line;
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) {
    line += buf;
    if (line.back() != '\n') continue;
    out << line;
    out.flush();
    line.pop_back();
    if (!echo.empty() && std::regex_search(line, re)) {
      std::printf("      %s\n", line.c_str());
      std::fflush(stdout);
    }
    line.clear();
  }
  if (!line.empty()) out << line << "\n";
  const int raw = pclose(pipe);
  if (raw == -1) return 127;
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  return 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
}

// Where the reports (OUT/gate) and the release artifact (OUT/release) go: out/ of the source
// tree unless --out names another folder (the README smoke test runs the gate into a temporary one).
std::string g_out;
std::string gate_dir() { return g_out + "/gate"; }
std::string release_dir() { return g_out + "/release"; }

std::string log_path(const char* id) { return gate_dir() + "/logs/" + id + ".log"; }

std::string self_exe() {
  std::error_code ec;
  const auto p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? build_dir("dev") + "/cli/axisproof" : p.string();
}

// ---- stages --------------------------------------------------------------------------

// The profile the gate judges (--profile, docs/profiles.md): its tests and fuzz targets carry
// its name as a ctest label, the harness's own checks the label harness; both run.
const Profile* g_profile = nullptr;
std::string profile_labels() { return "^(" + std::string(g_profile->name) + "|harness)$"; }

std::map<std::string, bool> built_ok;

bool cache_has(const std::string& preset, const std::string& entry) {
  return slurp(build_dir(preset) + "/CMakeCache.txt").find("\n" + entry + "\n") != std::string::npos;
}

// The asan build serves the coverage and fuzz smoke stages only with these switches on.
bool asan_shared() { return cache_has("asan", "AP_COVERAGE:BOOL=ON") && cache_has("asan", "AP_FUZZ_BINARIES:BOOL=ON"); }

int build_jobs() {
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 2;
}

// `target`: one target (and what it links) instead of everything.
Outcome build_stage(const std::string& preset, const std::string& log, const std::string& target = "") {
  std::string cmd;
  // A build tree configured before the preset gained its switches is configured again.
  if (!fs::exists(build_dir(preset) + "/CMakeCache.txt") || (preset == "asan" && !asan_shared())) {
    cmd = "cmake --preset " + preset + " && ";
  }
  cmd += "cmake --build --preset " + preset + " --parallel " + std::to_string(build_jobs()) +
         (target.empty() ? "" : " --target " + target);
  const int st = run_logged(cmd, log, R"(FAILED:|error:)");
  built_ok[preset] = st == 0;
  // Ninja's last progress line "[n/N]" tells how much was rebuilt.
  const std::string text = slurp(log);
  std::smatch m;
  std::string steps = "up to date";
  std::string::const_iterator from = text.begin();
  while (std::regex_search(from, text.end(), m, std::regex(R"(\[(\d+)/(\d+)\])"))) {
    steps = m[2].str() + " build steps";
    from = m.suffix().first;
  }
  if (st != 0) return {Result::Fail, "build failed (build/" + preset + ")"};
  return {Result::Pass, "build/" + preset + (target.empty() ? "" : " " + target) + ", " + steps};
}

int count_tests(const std::string& preset, const std::string& labels, const std::string& exclude = "") {
  int st = 0;
  const std::string out = run_capture("cd " + quote(source_dir()) + " && ctest --preset " + preset + " -N -L " + quote(labels) +
                                          " -L " + quote(profile_labels()) + (exclude.empty() ? "" : " -E " + quote(exclude)) +
                                          " 2>/dev/null", &st);
  std::smatch m;
  if (std::regex_search(out, m, std::regex(R"(Total Tests: (\d+))"))) return std::stoi(m[1].str());
  return 0;
}

std::string profile_dir() { return build_dir("asan") + "/profiles"; }

// `exclude` (a ctest -E regex, or empty): tests another stage runs in the same form.
Outcome ctest_stage(const std::string& labels, const std::string& junit, const std::string& log,
                    const std::string& exclude = "") {
  if (!built_ok["asan"]) return {Result::NotRun, "build (asan) failed"};
  const int n = count_tests("asan", labels);
  if (n == 0) return {Result::NotRun, "no tests labelled " + labels};
  const std::string except = exclude.empty() ? "" : " -E " + quote(exclude);
  const int st = run_logged("ctest --preset asan -L " + quote(labels) + " -L " + quote(profile_labels()) + except +
                                " --no-tests=error --output-junit " + quote(junit),
                            log, R"(\*\*\*Failed|\(Failed\)|\*\*\*Exception|\*\*\*Timeout|tests passed)");
  const std::string text = slurp(log);
  std::smatch m;
  std::string key = std::to_string(n) + " tests";
  if (std::regex_search(text, m, std::regex(R"((\d+)% tests passed, (\d+) tests? failed out of (\d+))"))) {
    key = m[3].str() + " tests, " + m[2].str() + " failed";
  }
  if (!exclude.empty()) {
    const int ran = count_tests("asan", labels, exclude);
    key += " (" + std::to_string(n - ran) + " that re-prove the obligations left to the proofs stage)";
  }
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

Outcome proofs_stage(gate::Run& run, const std::string& log) {
  if (g_profile->obligations == nullptr) return {Result::NotRun, "the profile has no proof obligations yet"};
  if (slurp(source_dir() + "/cli/cmd_prove.cpp").find("not available yet") != std::string::npos) {
    return {Result::NotRun, "axisproof prove is still the placeholder (docs/proofs.md)"};
  }
  // Both cores: the obligations are dealt to build_jobs() processes (axisproof prove --jobs).
  const int st = run_logged(quote(self_exe()) + " prove --profile " + std::string(g_profile->name) + " --jobs " +
                                std::to_string(build_jobs()),
                            log, R"(^\[\d+/\d+\])");
  const std::string text = slurp(log);
  if (text.find("not available yet") != std::string::npos) return {Result::NotRun, "axisproof prove not available yet"};
  // The final table: a header line starting with "obligation", rows until a blank line.
  std::istringstream in(text);
  std::string line;
  bool in_table = false;
  int proved = 0, other = 0;
  while (std::getline(in, line)) {
    if (!in_table) {
      if (line.rfind("obligation", 0) == 0 && line.find("result") != std::string::npos) in_table = true;
      continue;
    }
    if (trim(line).empty()) break;
    std::istringstream row(line);
    std::string name, result, secs, method;
    row >> name >> result >> secs;
    std::getline(row, method);
    run.details.proofs.push_back({name, result, secs, trim(method)});
    (result == "PROVED" ? proved : other)++;
  }
  std::string key = std::to_string(proved + other) + " obligations, " + std::to_string(proved) + " proved";
  if (proved + other == 0) key = st == 0 ? "prove passed (no table found)" : "prove failed (see log)";
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

int fuzz_seconds = 10;

long long stat_of(const std::string& text, const std::string& name) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex(name + R"(:\s*(\d+))"))) return std::stoll(m[1].str());
  return -1;
}

// Runs job(0) .. job(count - 1) on up to build_jobs() threads at once and returns when all are
// done. Each job writes its own files (the shared stage log is written afterwards, in order),
// so the stages whose parts are independent single-threaded processes (the fuzz smoke's
// targets, the QEMU scenarios) use both cores instead of one.
void run_parallel(std::size_t count, const std::function<void(std::size_t)>& job) {
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  const std::size_t n = std::min(count, static_cast<std::size_t>(build_jobs()));
  for (std::size_t i = 0; i < n; ++i) {
    pool.emplace_back([&] {
      for (std::size_t k = next++; k < count; k = next++) job(k);
    });
  }
  for (auto& t : pool) t.join();
}

// Where one target's short run keeps its corpus copy, findings and logs, and its bundled corpus.
std::string fuzz_out_dir(const FuzzTarget& t) { return gate_dir() + "/fuzz/" + t.name; }
std::string fuzz_corpus_dir(const FuzzTarget& t) { return t.data + "/corpus/" + t.name; }

// The short run of one target: the asan build's libFuzzer binary (ASan + UBSan) for `seconds`
// over a scratch corpus seeded from its corpus (fuzz/<profile>/corpus/<t>) (read-only), with its dictionary;
// new inputs and reproducers stay under out/gate/fuzz/<t>/, its output in fuzz.log there.
// Returns the exit status. Two targets run at once (run_parallel): the rates are those of a
// shared machine, as every rate the gate reports.
int fuzz_short_run(const FuzzTarget& t) {
  const std::string src = source_dir();
  const std::string dir = fuzz_out_dir(t);
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir + "/corpus");
  fs::create_directories(dir + "/findings");
  std::string dict;
  for (const auto& d : {t.data + "/dict/" + t.name + ".dict", t.data + "/dict/" + t.group + ".dict"}) {
    if (dict.empty() && fs::exists(d)) dict = d;
  }
  const std::string corpus = fuzz_corpus_dir(t);
  std::string cmd = "LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 "
                    "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 " + quote(t.binary) +
                    " -max_total_time=" + std::to_string(fuzz_seconds) + " -print_final_stats=1 -seed=1" +
                    " -artifact_prefix=" + quote(dir + "/findings/") + (dict.empty() ? "" : " -dict=" + quote(dict)) + " " +
                    quote(dir + "/corpus") + (fs::is_directory(corpus) ? " " + quote(corpus) : "");
  return run_logged(cmd + " >" + quote(dir + "/fuzz.log") + " 2>&1", dir + "/command.log");
}

// Reads one target's short run (fuzz_short_run) into the report and the stage log.
void fuzz_collect(const FuzzTarget& t, int st, gate::Run& run, const std::string& log, int* findings, bool* ok,
                  long long* min_rate, std::string* slowest) {
  const std::string dir = fuzz_out_dir(t);
  const std::string corpus = fuzz_corpus_dir(t);
  std::error_code ec;
  const std::string text = slurp(dir + "/fuzz.log");
  {
    std::ofstream out(log, std::ios::app);
    out << slurp(dir + "/command.log") << text;
  }
  const long long execs = stat_of(text, "stat::number_of_executed_units");
  const long long rate = stat_of(text, "stat::average_exec_per_sec");
  long long cov = -1;
  const std::regex cov_re(R"(cov: (\d+))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), cov_re); it != std::sregex_iterator(); ++it) {
    cov = std::stoll((*it)[1].str());
  }
  int found = 0;
  for (const auto& e : fs::directory_iterator(dir + "/findings", ec)) found += e.is_regular_file() ? 1 : 0;
  if (st != 0 && found == 0) found = 1;  // died without an artifact: still a finding
  long long corpus_files = 0;
  for (const auto& d : {dir + "/corpus", corpus}) {
    for (const auto& e : fs::directory_iterator(d, ec)) corpus_files += e.is_regular_file() ? 1 : 0;
  }
  if (execs < 0) *ok = false;  // the binary did not run as a fuzzer
  *findings += found;
  if (rate >= 0 && (*min_rate < 0 || rate < *min_rate)) {
    *min_rate = rate;
    *slowest = t.name;
  }
  run.details.fuzz.push_back({t.name, std::to_string(execs), std::to_string(rate), std::to_string(corpus_files),
                              std::to_string(cov), std::to_string(found)});
  std::printf("      %-20s %9lld execs %7lld exec/s  cov %lld  %s\n", t.name.c_str(), execs, rate, cov,
              found ? "FINDING (out/gate/fuzz/<t>/findings/)" : "no finding");
  std::fflush(stdout);
}

Outcome fuzz_stage(gate::Run& run, const std::string& log) {
  if (!built_ok["asan"]) return {Result::NotRun, "build (asan) failed"};
  const std::vector<FuzzTarget> listed = read_fuzz_targets(build_dir("asan"), g_profile->name);
  if (listed.empty()) return {Result::NotRun, "no fuzz targets of this profile (fuzz/<group>/ with ap_add_fuzz_target)"};
  const std::string not_cfl = " -L " + quote(profile_labels()) + " -E '^fuzz\\.clusterfuzzlite_build_sh$'";
  int st = 0;
  const std::string n_out = run_capture("cd " + quote(source_dir()) + " && ctest --preset asan -N -L fuzz" + not_cfl + " 2>/dev/null", &st);
  std::smatch nm;
  const int replays = std::regex_search(n_out, nm, std::regex(R"(Total Tests: (\d+))")) ? std::stoi(nm[1].str()) : 0;
  st = run_logged("ctest --preset asan -L fuzz" + not_cfl + " --no-tests=error --output-junit " +
                      quote(gate_dir() + "/junit-fuzz-replay.xml"),
                  log, R"(\*\*\*Failed|\(Failed\)|\*\*\*Exception|\*\*\*Timeout|tests passed)");
  if (st != 0) return {Result::Fail, "replay of corpora / regressions fails (" + std::to_string(replays) + " fuzz tests)"};
  std::vector<FuzzTarget> runnable;
  for (const auto& t : listed) {
    if (t.binary != "-" && fs::exists(t.binary)) runnable.push_back(t);
  }
  if (runnable.size() != listed.size()) {
    return {Result::NotRun, std::to_string(replays) + " replay tests passed; build/asan has no libFuzzer binaries "
                            "(configure it from the asan preset: AP_FUZZ_BINARIES)"};
  }
  bool ok = true;
  int findings = 0;
  long long min_rate = -1;
  std::string slowest;
  std::vector<int> status(runnable.size(), 0);
  run_parallel(runnable.size(), [&](std::size_t i) { status[i] = fuzz_short_run(runnable[i]); });
  for (std::size_t i = 0; i < runnable.size(); ++i) {
    fuzz_collect(runnable[i], status[i], run, log, &findings, &ok, &min_rate, &slowest);
  }
  std::string key = std::to_string(replays) + " replay tests; " + std::to_string(runnable.size()) + " targets x " +
                    std::to_string(fuzz_seconds) + " s, " + std::to_string(findings) + " findings";
  if (min_rate >= 0) key += ", slowest " + slowest + " " + std::to_string(min_rate) + " exec/s";
  if (!ok) return {Result::Fail, key + " (a target did not run as a fuzzer; see log)"};
  return {findings == 0 ? Result::Pass : Result::Fail, key + (findings ? " (reproducers in out/gate/fuzz/<target>/findings/)" : "")};
}

Outcome e2e_stage(const std::string& log) {
  if (!built_ok["asan"]) return {Result::NotRun, "build (asan) failed"};
  if (count_tests("asan", "e2e") == 0) return {Result::NotRun, "no end-to-end tests (ctest label e2e) yet"};
  return ctest_stage("e2e", gate_dir() + "/junit-e2e.xml", log);
}

Outcome mutation_stage(gate::Run& run, const std::string& log) {
  // The runner picks a profile's mutants by their Profile: header; asked first for the
  // profile's own, so a profile without any is NOT RUN rather than judged on the harness's.
  int listed = 0;
  const std::string own = run_capture("cd " + quote(source_dir()) + " && ci/mutate --list --profile " +
                                          std::string(g_profile->name) + " 2>/dev/null",
                                      &listed);
  if (listed != 0 || trim(own).empty()) return {Result::NotRun, "no mutants of this profile in ci/mutants/"};
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
  // The profile's mutants and the harness's own (README, bootstrap, CLI), like the tests.
  const int st = run_logged("ci/mutate --builds asan --profile " + std::string(g_profile->name) + ",harness --jobs " +
                                std::to_string(build_jobs()) +
                                (earlier_pass ? " --no-wide-baseline --no-ctest-baseline" : ""),
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
    ++total;
    if (f[2].rfind("killed", 0) == 0) ++killed;
    else bad.push_back(f[0] + " " + (f[2] == "SURVIVED" ? "SURVIVED" : "INVALID"));
  }
  const std::string text = slurp(log);
  std::smatch m;
  if (std::regex_search(text, m, std::regex(R"(mutation suite: ([^\n]*))"))) run.details.mutation_summary = m[1].str();
  if (total == 0) return {Result::Fail, "runner failed before any mutant (baseline or build; see log)"};
  std::string key = std::to_string(killed) + "/" + std::to_string(total) + " killed";
  for (size_t i = 0; i < bad.size() && i < 3; ++i) key += (i ? ", " : "; ") + bad[i];
  if (bad.size() > 3) key += ", ...";
  return {st == 0 && killed == total ? Result::Pass : Result::Fail, key};
}

Outcome coverage_stage(gate::Run& run, const std::string& log) {
  char thr[16];
  std::snprintf(thr, sizeof thr, "%.0f", kMinBranchCoverage);
  // The test stages of the asan build wrote the profiles; without them (an asan build without
  // coverage), ci/coverage builds the cov preset and runs the suite again.
  const bool shared = asan_shared() && fs::is_directory(profile_dir()) && !fs::is_empty(profile_dir());
  const std::string from = shared ? " --build-dir " + quote(build_dir("asan")) + " --profiles " + quote(profile_dir()) : "";
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
// for byte. The shortest one runs on the image twice: the same scenario gives the same trace.
Outcome qemu_stage(gate::Run& run, const std::string& log) {
  const bool m4_ok = std::any_of(run.rows.begin(), run.rows.end(), [](const gate::Row& r) {
    return r.stage == "cortex-m4 build" && r.outcome.result == Result::Pass;
  });
  if (!m4_ok) return {Result::NotRun, "the cortex-m4 build did not pass: no image"};
  const std::string root = gate_dir() + "/qemu";
  const std::string self = quote(self_exe());
  const auto stats = [](const std::string& file) {
    std::map<std::string, std::string> kv;
    std::ifstream in(file);
    std::string k, v;
    while (in >> k >> v) kv[k] = v;
    return kv;
  };
  int passed = 0;
  double emulated = 0, wall = 0;
  unsigned long stack = 0, stack_size = 0;
  std::vector<std::string> bad;
  std::string shortest;
  unsigned long shortest_ticks = 0;
  // Two scenarios at once (run_parallel): each run is one emulator and one mirror process
  // taking turns, about one core. Each writes its own log, appended to the stage's in order.
  const std::vector<std::string_view>& names = g_profile->qemu_scenarios;
  std::vector<int> host_st(names.size(), 0), image_st(names.size(), 0);
  run_parallel(names.size(), [&](std::size_t i) {
    const std::string name(names[i]);
    const std::string scn = scenarios_dir(*g_profile) + "/" + name + ".scn";
    const std::string own = root + "/logs/" + name + ".log";
    std::error_code rm_ec;
    fs::remove(own, rm_ec);
    host_st[i] = run_logged(self + " sim run --profile " + std::string(g_profile->name) + " " + quote(scn) + " --out " + quote(root + "/host"), own);
    image_st[i] = run_logged(self + " sim run --profile " + std::string(g_profile->name) + " " + quote(scn) + " --target qemu --out " + quote(root + "/qemu"), own,
                             "^scenario ");
  });
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string name(names[i]);
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
      const unsigned long ticks = std::stoul(kv.at("ticks"));
      emulated += std::stod(kv.at("emulated_s"));
      wall += std::stod(kv.at("wall_s"));
      stack = std::max(stack, std::stoul(kv.at("stack_used")));
      stack_size = std::stoul(kv.at("stack_size"));
      if (shortest.empty() || ticks < shortest_ticks) {
        shortest = name;
        shortest_ticks = ticks;
      }
    }
    if (host == 0 && image == 0 && same) {
      ++passed;
    } else {
      bad.push_back(name + (image != 0 ? " FAIL on the image" : host != 0 ? " FAIL on the host" : " traces differ"));
    }
  }
  bool repeatable = false;
  if (!shortest.empty()) {
    const std::string scn = scenarios_dir(*g_profile) + "/" + shortest + ".scn";
    const int again = run_logged(self + " sim run --profile " + std::string(g_profile->name) + " " + quote(scn) + " --target qemu --out " + quote(root + "/again"), log);
    repeatable = again == 0 && slurp(root + "/again/" + shortest + "/trace.csv") == slurp(root + "/qemu/" + shortest + "/trace.csv");
    if (!repeatable) bad.push_back(shortest + " gave another trace the second time");
  }
  const std::size_t n = g_profile->qemu_scenarios.size();
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%d/%zu scenarios PASS on the image, traces equal to the host's%s; emulated %.1f s in %.1f s wall (%.2fx, "
                "two runs at once); "
                "stack high-water %lu of %lu B",
                passed, n, repeatable ? ", repeatable" : "", emulated, wall, wall > 0 ? emulated / wall : 0.0, stack, stack_size);
  std::string key = buf;
  for (std::size_t i = 0; i < bad.size() && i < 3; ++i) key += (i ? ", " : "; ") + bad[i];
  return {passed == static_cast<int>(n) && repeatable && n > 0 ? Result::Pass : Result::Fail, key};
}

// The README's `axisproof bench` end to end (release benchmarks build, one benchmark runs): a
// smoke of the command, not a performance check, so the rate is reported and never judged.
Outcome bench_stage(const std::string& log) {
  const char* kBenchmark = "BM_ProtocolParseCommand";
  const int st = run_logged(quote(self_exe()) + " bench --filter '^" + kBenchmark + "$'", log, std::string("^") + kBenchmark);
  std::smatch m;
  const std::string text = slurp(log);
  std::string key = st == 0 ? "ran" : "bench failed (see log)";
  if (std::regex_search(text, m, std::regex(std::string(kBenchmark) + R"(\s+\S+ ns\s+\S+ ns\s+\d+\s+(\S+/s))")))
    key = std::string(kBenchmark) + " " + m[1].str() + " (CPU time, release build)";
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace

void add_gate(CLI::App& app) {
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
  sub->final_callback([] {
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
         [](gate::Run&, std::string& l) {
           std::error_code rm_ec;
           fs::remove_all(profile_dir(), rm_ec);  // the coverage stage reads what this and the later test stages write
           // The tests that prove the profile's whole obligation registry again (each module's
           // "every obligation is PROVED") are left to the proofs stage, which proves the same
           // list with the same solver and reports each obligation.
           return ctest_stage("unit|property|proof", gate_dir() + "/junit-tests.xml", l, std::string(g_profile->registry_tests));
         }},
        {"proofs", "proofs", [](gate::Run& r, std::string& l) { return proofs_stage(r, l); }},
        {"fuzz", "fuzz smoke", [](gate::Run& r, std::string& l) { return fuzz_stage(r, l); }},
        {"e2e", "end-to-end scenarios", [](gate::Run&, std::string& l) { return e2e_stage(l); }},
        {"mutation", "mutation suite", [](gate::Run& r, std::string& l) { return mutation_stage(r, l); }},
        {"coverage", "coverage", [](gate::Run& r, std::string& l) { return coverage_stage(r, l); }},
        {"m4", "cortex-m4 build", [](gate::Run& r, std::string& l) { return m4_stage(r, l); }},
        {"bench", "benchmarks (release)", [](gate::Run&, std::string& l) { return bench_stage(l); }},
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
      run.rows.push_back({s.name, o, secs, rel});
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
    gate::print_table(run);
    gate::write_reports(run, gate_dir());
    gate::write_manifest(run, release_dir());
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
