// The release gate's checking stages: proofs (`axisproof prove`), the fuzz smoke (replays, then
// a short run of every libFuzzer target) and the end-to-end scenarios. Split out of
// cmd_gate.cpp to keep each file of the gate readable; the stages are described in
// docs/architecture.md, "The release gate" (see gate_stages.hpp).
#include "cli.hpp"
#include "fuzz_run.hpp"
#include "gate_shard.hpp"
#include "gate_stages.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli::gate_stages {

Outcome proofs_stage(gate::Run& run, const std::string& log) {
  if (g_profile->obligations == nullptr) return {Result::NotRun, "the profile has no proof obligations yet"};
  if (slurp(source_dir() + "/cli/cmd_prove.cpp").find("not available yet") != std::string::npos) {
    return {Result::NotRun, "axisproof prove is still the placeholder (docs/proofs.md)"};
  }
  // A shard proves its own obligations (--only NAME; --only also takes a prefix, so the table
  // is read for exactly those names below).
  std::vector<std::string> all;
  for (const auto& o : g_profile->obligations()) all.push_back(o.name);
  const std::vector<std::string> mine = my_parts("proofs", all);
  if (mine.empty()) return {Result::Pass, "0 of " + std::to_string(all.size()) + " obligations in shard " + shard_text()};
  std::string only;
  if (g_shard.on()) {
    for (const auto& n : mine) only += " --only " + quote(n);
  }
  // Both cores: the obligations are dealt to build_jobs() processes (axisproof prove --jobs).
  const int st = run_logged(quote(self_exe()) + " prove --profile " + std::string(g_profile->name) + only + " --jobs " +
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
    if (std::find(mine.begin(), mine.end(), name) == mine.end()) continue;  // another shard's, matched by prefix
    run.details.proofs.push_back({name, result, secs, trim(method)});
    double s = 0;
    try {
      s = std::stod(secs);
    } catch (...) {
    }
    run.items["proofs"].push_back({name, result, result == "PROVED", s});
    (result == "PROVED" ? proved : other)++;
  }
  std::string key = std::to_string(proved + other) + " obligations" +
                    (g_shard.on() ? " of " + std::to_string(all.size()) + " in shard " + shard_text() : "") + ", " +
                    std::to_string(proved) + " proved";
  if (proved + other == 0) key = st == 0 ? "prove passed (no table found)" : "prove failed (see log)";
  if (proved + other != static_cast<int>(mine.size())) {
    return {Result::Fail, key + "; the table has " + std::to_string(proved + other) + " of the " + std::to_string(mine.size()) + " obligations asked"};
  }
  return {st == 0 ? Result::Pass : Result::Fail, key};
}

int fuzz_seconds = 10;

namespace {

long long stat_of(const std::string& text, const std::string& name) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex(name + R"(:\s*(\d+))"))) return std::stoll(m[1].str());
  return -1;
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

}  // namespace

Outcome fuzz_stage(gate::Run& run, const std::string& log) {
  if (!built_ok["asan"]) return {Result::NotRun, "build (asan) failed"};
  const std::vector<FuzzTarget> listed = read_fuzz_targets(build_dir("asan"), g_profile->name);
  if (listed.empty()) return {Result::NotRun, "no fuzz targets of this profile (fuzz/<group>/ with ap_add_fuzz_target)"};
  // The replays and the short runs are parts of the shard plan: "NAME" for a replay test,
  // "target:T" for a short run (gate_shard.cpp).
  const std::vector<std::string> replays_all = ctest_names("fuzz", fuzz_replay_exclude());
  const std::vector<std::string> replays = my_parts("fuzz", replays_all);
  std::vector<FuzzTarget> mine;
  for (const auto& t : listed) {
    if (my_part("fuzz", "target:" + t.name)) mine.push_back(t);
  }
  const std::string part = g_shard.on() ? " in shard " + shard_text() : "";
  auto& items = run.items["fuzz"];
  if (!replays.empty()) {
    const std::string junit = gate_dir() + "/junit-fuzz-replay.xml";
    std::error_code ec;
    fs::remove(junit, ec);
    const std::string only = g_shard.on() ? " -R " + quote(exact_regex(replays)) : "";
    const int st = run_logged("ctest --preset asan -L fuzz -L " + quote(profile_labels()) + " -E " + quote(fuzz_replay_exclude()) +
                                  only + " --no-tests=error --output-junit " + quote(junit),
                              log, R"(\*\*\*Failed|\(Failed\)|\*\*\*Exception|\*\*\*Timeout|tests passed)");
    items = read_ctest_junit(junit);
    const bool all_ran = items.size() == replays.size();
    if (st != 0 || !all_ran) {
      return {Result::Fail, "replay of corpora / regressions fails (" + std::to_string(replays.size()) + " fuzz tests" + part +
                                (all_ran ? "" : "; ctest ran " + std::to_string(items.size())) + ")"};
    }
  }
  std::vector<FuzzTarget> runnable;
  for (const auto& t : mine) {
    if (t.binary != "-" && fs::exists(t.binary)) runnable.push_back(t);
  }
  if (runnable.size() != mine.size()) {
    return {Result::NotRun, std::to_string(replays.size()) + " replay tests passed; build/asan has no libFuzzer binaries "
                            "(configure it from the asan preset: AP_FUZZ_BINARIES)"};
  }
  bool ok = true;
  int findings = 0;
  long long min_rate = -1;
  std::string slowest;
  std::vector<int> status(runnable.size(), 0);
  std::vector<double> secs(runnable.size(), 0.0);
  run_parallel(runnable.size(), [&](std::size_t i) {
    const auto t0 = std::chrono::steady_clock::now();
    status[i] = fuzz_short_run(runnable[i]);
    secs[i] = seconds_since(t0);
  });
  for (std::size_t i = 0; i < runnable.size(); ++i) {
    const int before = findings;
    bool ran = true;
    fuzz_collect(runnable[i], status[i], run, log, &findings, &ran, &min_rate, &slowest);
    ok = ok && ran;
    const bool clean = ran && findings == before;
    items.push_back({"target:" + runnable[i].name, clean ? "no finding" : ran ? "finding" : "did not run", clean, secs[i]});
  }
  std::string key = std::to_string(replays.size()) + " replay tests; " + std::to_string(runnable.size()) + " targets x " +
                    std::to_string(fuzz_seconds) + " s" + part + ", " + std::to_string(findings) + " findings";
  if (min_rate >= 0) key += ", slowest " + slowest + " " + std::to_string(min_rate) + " exec/s";
  if (!ok) return {Result::Fail, key + " (a target did not run as a fuzzer; see log)"};
  return {findings == 0 ? Result::Pass : Result::Fail, key + (findings ? " (reproducers in out/gate/fuzz/<target>/findings/)" : "")};
}

Outcome e2e_stage(gate::Run& run, const std::string& log) {
  if (!built_ok["asan"]) return {Result::NotRun, "build (asan) failed"};
  if (count_tests("asan", "e2e") == 0) return {Result::NotRun, "no end-to-end tests (ctest label e2e) yet"};
  return ctest_stage(run, "e2e", "e2e", gate_dir() + "/junit-e2e.xml", log);
}

}  // namespace ap::cli::gate_stages
