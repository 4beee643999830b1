// The release gate's build and ctest stages, and the helpers every stage shares (running a
// logged command, the output folders, the profile's ctest labels, running parts in parallel).
// Split out of cmd_gate.cpp to keep each file of the gate readable; the stages and the gate's
// design are described in docs/architecture.md, "The release gate" (see gate_stages.hpp).
#include "cli.hpp"
#include "gate_shard.hpp"
#include "gate_stages.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli::gate_stages {

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

// Runs a shell command in the source dir, output (stdout + stderr) to `log`; lines matching
// `echo` are shown indented, as progress. Returns the exit status.
int run_logged(const std::string& command, const std::string& log, const std::string& echo) {
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

std::string self_exe() {
  std::error_code ec;
  const auto p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return build_dir("dev") + "/cli/axisproof";
  // The build (dev) stage may have relinked this very executable: the kernel then names the
  // running one "PATH (deleted)", and PATH holds the new one, built from the same sources.
  std::string path = p.string();
  const std::string deleted = " (deleted)";
  if (path.size() > deleted.size() && path.compare(path.size() - deleted.size(), deleted.size(), deleted) == 0) {
    path.resize(path.size() - deleted.size());
  }
  return path;
}

// The profile the gate judges (--profile, docs/profiles.md): its tests and fuzz targets carry
// its name as a ctest label, the harness's own checks the label harness; both run.
const Profile* g_profile = nullptr;
std::string profile_labels() { return "^(" + std::string(g_profile->name) + "|harness)$"; }

std::map<std::string, bool> built_ok;

namespace {

bool cache_has(const std::string& preset, const std::string& entry) {
  return slurp(build_dir(preset) + "/CMakeCache.txt").find("\n" + entry + "\n") != std::string::npos;
}

}  // namespace

// The asan build serves the coverage and fuzz smoke stages only with these switches on.
bool asan_shared() { return cache_has("asan", "AP_COVERAGE:BOOL=ON") && cache_has("asan", "AP_FUZZ_BINARIES:BOOL=ON"); }

int build_jobs() {
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 2;
}

// `target`: one target (and what it links) instead of everything.
Outcome build_stage(const std::string& preset, const std::string& log, const std::string& target) {
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

int count_tests(const std::string& preset, const std::string& labels, const std::string& exclude) {
  int st = 0;
  const std::string out = run_capture("cd " + quote(source_dir()) + " && ctest --preset " + preset + " -N -L " + quote(labels) +
                                          " -L " + quote(profile_labels()) + (exclude.empty() ? "" : " -E " + quote(exclude)) +
                                          " 2>/dev/null", &st);
  std::smatch m;
  if (std::regex_search(out, m, std::regex(R"(Total Tests: (\d+))"))) return std::stoi(m[1].str());
  return 0;
}

std::string profile_dir() { return build_dir("asan") + "/profiles"; }

// `exclude` (a ctest -E regex, or empty): tests another stage runs in the same form. `id`:
// the stage's id, the name of its parts in the shard plan (gate_shard.hpp); a shard runs only
// its own tests (ctest -R with their exact names).
Outcome ctest_stage(gate::Run& run, const std::string& id, const std::string& labels, const std::string& junit,
                    const std::string& log, const std::string& exclude) {
  if (!built_ok["asan"]) return {Result::NotRun, "build (asan) failed"};
  const std::vector<std::string> all = ctest_names(labels, exclude);
  if (all.empty()) return {Result::NotRun, "no tests labelled " + labels};
  const std::vector<std::string> mine = my_parts(id, all);
  const std::string part = g_shard.on() ? " of " + std::to_string(all.size()) + " in shard " + shard_text() : "";
  if (mine.empty()) return {Result::Pass, "0" + part};
  const std::string except = exclude.empty() ? "" : " -E " + quote(exclude);
  const std::string only = g_shard.on() ? " -R " + quote(exact_regex(mine)) : "";
  std::error_code ec;
  fs::remove(junit, ec);
  const int st = run_logged("ctest --preset asan -L " + quote(labels) + " -L " + quote(profile_labels()) + except + only +
                                " --no-tests=error --output-junit " + quote(junit),
                            log, R"(\*\*\*Failed|\(Failed\)|\*\*\*Exception|\*\*\*Timeout|tests passed)");
  auto& items = run.items[id];
  items = read_ctest_junit(junit);
  const auto failed = std::count_if(items.begin(), items.end(), [](const gate::Item& i) { return !i.pass; });
  std::string key = std::to_string(items.size()) + " tests" + part + ", " + std::to_string(failed) + " failed";
  if (!exclude.empty()) {
    const int everything = count_tests("asan", labels);
    key += " (" + std::to_string(everything - static_cast<int>(all.size())) + " that re-prove the obligations left to the proofs stage)";
  }
  if (items.size() != mine.size()) {
    return {Result::Fail, key + "; ctest ran " + std::to_string(items.size()) + " of the " + std::to_string(mine.size()) + " tests asked"};
  }
  return {st == 0 && failed == 0 ? Result::Pass : Result::Fail, key};
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

}  // namespace ap::cli::gate_stages
