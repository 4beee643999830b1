// One libFuzzer target's run for `axisproof fuzz` (cmd_fuzz.cpp): fork-mode fuzzing with the
// progress line, the merge into its corpus, and the minimisation of each distinct finding into
// a reproducer. Split out of cmd_fuzz.cpp to keep each file readable; the profile's fuzz folders
// it reads and writes are described in docs/profiles.md, the fuzz preset in docs/architecture.md.
// Its helpers live in ap::cli::fuzz_engine, so their names cannot meet
// another command's file-local helpers in the unity build (cli/CMakeLists.txt).
#include "cli.hpp"
#include "fuzz_run.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli::fuzz_engine {

namespace {

// Runs a command, feeding each output line (stdout + stderr) to `on_line`; returns the status.
template <typename F>
int run_lines(const std::string& command_line, F&& on_line) {
  std::fflush(stdout);
  FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return 127;
  std::string line;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      on_line(line);
      line.clear();
    }
  }
  if (!line.empty()) on_line(line);
  const int raw = pclose(pipe);
  if (raw == -1) return 127;
  if (WIFEXITED(raw)) return WEXITSTATUS(raw);
  return 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
}

long long count_files(const fs::path& dir) {
  long long n = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const auto name = e.path().filename().string();
    if (e.is_regular_file() && name[0] != '.' && e.path().extension() != ".txt" && e.path().extension() != ".md") ++n;
  }
  return n;
}

std::string today() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::gmtime(&t));
  return buf;
}

const std::string kSanitizerEnv =
    "ASAN_OPTIONS=abort_on_error=1:detect_leaks=1:symbolize=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ";

// Crash signature: the sanitizer summary plus up to three stack frames inside the tree
// (function and file:line, without addresses or columns).
struct Signature {
  std::string kind;     // crash, leak, timeout, oom
  std::string summary;  // "AddressSanitizer: heap-buffer-overflow", "libFuzzer: deadly signal", ...
  std::string frames;   // "parse core/<profile>/frame/src/frame.cpp:12 < LLVMFuzzerTestOneInput fuzz/..."
  bool reproduced = false;
  std::string key() const { return summary + " | " + frames; }
};

Signature signature_of(const std::string& binary, const fs::path& input, const std::string& kind) {
  Signature s;
  s.kind = kind;
  const std::string src = source_dir() + "/";
  const std::regex frame_re(R"(^\s+#\d+ 0x[0-9a-f]+ in (.+?) (/\S+?):(\d+)(:\d+)?$)");
  const std::regex summary_re(R"(^SUMMARY: (\S+: [^ ]+( [^ /]+)?))");
  std::vector<std::string> frames;
  const int status = run_lines(kSanitizerEnv + quote(binary) + " -timeout=10 -rss_limit_mb=2048 " + quote(input.string()),
                               [&](const std::string& line) {
                                 std::smatch m;
                                 if (s.summary.empty() && std::regex_search(line, m, summary_re)) s.summary = m[1].str();
                                 if (frames.size() < 3 && std::regex_match(line, m, frame_re)) {
                                   std::string file = m[2].str();
                                   if (file.rfind(src, 0) == 0 && file.find("/fuzz/kit/src/replay_main.cpp") == std::string::npos) {
                                     std::string fn = m[1].str();
                                     fn = fn.substr(0, fn.find('('));
                                     frames.push_back(fn + " " + file.substr(src.size()) + ":" + m[3].str());
                                   }
                                 }
                                 if (line.find("ERROR: libFuzzer: timeout") != std::string::npos && s.summary.empty()) {
                                   s.summary = "libFuzzer: timeout";
                                 }
                               });
  s.reproduced = status != 0;
  for (size_t i = 0; i < frames.size(); ++i) s.frames += (i ? " < " : "") + frames[i];
  if (s.summary.empty()) s.summary = s.reproduced ? "exit status " + std::to_string(status) : "does not reproduce";
  return s;
}

// Signatures already recorded in fuzz/regressions/<t>/*.txt ("... signature: <key>").
std::set<std::string> known_signatures(const fs::path& dir) {
  std::set<std::string> known;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return known;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() != ".txt") continue;
    std::ifstream in(e.path());
    std::string line;
    while (std::getline(in, line)) {
      const auto p = line.find("signature: ");
      if (p != std::string::npos) known.insert(line.substr(p + 11));
    }
  }
  return known;
}

}  // namespace

FuzzStats fuzz_one(const FuzzTarget& t, const FuzzOptions& o) {
  FuzzStats st;
  st.target = t.name;
  const fs::path src = source_dir();
  const fs::path work = src / "out" / "fuzz" / t.name;
  const fs::path fresh = work / "new";
  const fs::path artifacts = work / "artifacts";
  const fs::path corpus = fs::path(t.data) / "corpus" / t.name;
  const fs::path regressions = o.no_save ? work / "findings" : fs::path(t.data) / "regressions" / t.name;
  std::error_code ec;
  fs::remove_all(fresh, ec);
  fs::remove_all(artifacts, ec);
  fs::create_directories(fresh);
  fs::create_directories(artifacts);
  fs::create_directories(corpus);

  std::string dict;
  for (const auto& d : {fs::path(t.data) / "dict" / (t.name + ".dict"), fs::path(t.data) / "dict" / (t.group + ".dict")}) {
    if (fs::exists(d)) {
      dict = d.string();
      break;
    }
  }

  // <data>/<group>/<target>.options (beside the target's sources; <data>/<target>.options when
  // the target's folder is the profile's fuzz folder itself): OSS-Fuzz's format ([libfuzzer]
  // then key = value lines), passed as -key=value; ClusterFuzzLite reads the same file
  // (.clusterfuzzlite/build.sh).
  std::string extra;
  {
    fs::path options = fs::path(t.data) / t.group / (t.name + ".options");
    if (!fs::exists(options)) options = fs::path(t.data) / (t.name + ".options");
    std::ifstream opt(options);
    std::string line;
    bool in_libfuzzer = false;
    while (std::getline(opt, line)) {
      line.erase(0, line.find_first_not_of(" \t"));
      if (line.empty() || line[0] == '#') continue;
      if (line[0] == '[') {
        in_libfuzzer = line.rfind("[libfuzzer]", 0) == 0;
        continue;
      }
      const auto eq = line.find('=');
      if (!in_libfuzzer || eq == std::string::npos) continue;
      auto trim = [](std::string v) {
        v.erase(0, v.find_first_not_of(" \t"));
        v.erase(v.find_last_not_of(" \t\r") + 1);
        return v;
      };
      extra += " -" + trim(line.substr(0, eq)) + "=" + quote(trim(line.substr(eq + 1)));
    }
  }
  std::string cmd = "cd " + quote(work.string()) + " && " + kSanitizerEnv + quote(t.binary) + extra +
                    " -fork=" + std::to_string(std::max(1, o.jobs)) + " -max_total_time=" + std::to_string(o.seconds) +
                    " -timeout=10 -rss_limit_mb=2048 -ignore_crashes=1 -print_final_stats=1 -artifact_prefix=" +
                    quote(artifacts.string() + "/");
  if (!dict.empty()) cmd += " -dict=" + quote(dict);
  cmd += " " + quote(fresh.string()) + " " + quote(corpus.string());

  const bool tty = isatty(1) != 0;
  const std::regex progress(R"(^#(\d+): cov: (\d+) ft: \d+ corp: (\d+) exec/s \d+ oom/timeout/crash: (\d+)/(\d+)/(\d+) time: (\d+)s)");
  std::ofstream log(work / "fuzz.log");
  long long crashes = 0;
  long long last_print = -1;
  const auto start = std::chrono::steady_clock::now();
  std::printf("fuzz %s: %d s, -fork=%d%s\n", t.name.c_str(), o.seconds, o.jobs,
              dict.empty() ? "" : (", dictionary " + fs::path(dict).filename().string()).c_str());
  const int status = run_lines(cmd, [&](const std::string& line) {
    log << line << "\n";
    std::smatch m;
    if (!std::regex_search(line, m, progress)) return;
    st.executions = std::stoll(m[1].str());
    st.coverage = std::stoll(m[2].str());
    crashes = std::stoll(m[4].str()) + std::stoll(m[5].str()) + std::stoll(m[6].str());
    const long long secs = std::stoll(m[7].str());
    const double el = std::max(1.0, seconds_since(start));
    st.exec_per_s = static_cast<long long>(static_cast<double>(st.executions) / el);
    if (tty) {
      std::printf("\r  [%s] %3llds/%ds  execs %lld  exec/s %lld  cov %lld  corpus %s  oom/timeout/crash %s/%s/%s   ",
                  t.name.c_str(), secs, o.seconds, st.executions, st.exec_per_s, st.coverage, m[3].str().c_str(),
                  m[4].str().c_str(), m[5].str().c_str(), m[6].str().c_str());
      std::fflush(stdout);
    } else if (secs / 10 != last_print / 10 || last_print < 0) {
      last_print = secs;
      std::printf("  [%s] %llds/%ds  execs %lld  exec/s %lld  cov %lld  corpus %s  oom/timeout/crash %s/%s/%s\n",
                  t.name.c_str(), secs, o.seconds, st.executions, st.exec_per_s, st.coverage, m[3].str().c_str(),
                  m[4].str().c_str(), m[5].str().c_str(), m[6].str().c_str());
    }
  });
  if (tty) std::printf("\n");
  st.seconds = seconds_since(start);
  st.exec_per_s = static_cast<long long>(static_cast<double>(st.executions) / std::max(1.0, st.seconds));
  log.close();
  st.ran = st.executions > 0 || status == 0;
  if (!st.ran) {
    st.note = "libFuzzer did not run (status " + std::to_string(status) + "), see out/fuzz/" + t.name + "/fuzz.log";
    return st;
  }

  // Merge: keep only the new inputs that add coverage to the committed corpus.
  const fs::path merge_into = o.no_save ? work / "corpus" : corpus;
  if (o.no_save) {
    fs::remove_all(merge_into, ec);
    fs::create_directories(merge_into);
    for (const auto& e : fs::directory_iterator(corpus)) fs::copy(e.path(), merge_into / e.path().filename(), ec);
  }
  const long long before = count_files(merge_into);
  run_lines(kSanitizerEnv + quote(t.binary) + " -merge=1 -timeout=10 -rss_limit_mb=2048 -artifact_prefix=" +
                quote(artifacts.string() + "/") + " " + quote(merge_into.string()) + " " + quote(fresh.string()),
            [](const std::string&) {});
  st.corpus_files = count_files(merge_into);
  st.new_inputs = static_cast<int>(st.corpus_files - before);

  // Findings: distinct signatures among the artifacts, smallest first, bounded work.
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(artifacts)) {
    const auto n = e.path().filename().string();
    if (n.rfind("crash-", 0) == 0 || n.rfind("leak-", 0) == 0 || n.rfind("timeout-", 0) == 0 || n.rfind("oom-", 0) == 0) {
      found.push_back(e.path());
    }
  }
  std::sort(found.begin(), found.end(), [](const fs::path& a, const fs::path& b) {
    return fs::file_size(a) != fs::file_size(b) ? fs::file_size(a) < fs::file_size(b) : a < b;
  });
  if (found.size() > 30) found.resize(30);
  const std::set<std::string> known = known_signatures(regressions);
  std::map<std::string, std::pair<fs::path, Signature>> distinct;
  for (const auto& f : found) {
    const std::string name = f.filename().string();
    Signature s = signature_of(t.binary, f, name.substr(0, name.find('-')));
    if (!s.reproduced) s.summary = "flaky (does not reproduce alone)";
    distinct.emplace(s.key(), std::make_pair(f, s));
  }
  if (crashes > 0 && distinct.empty()) distinct.emplace("unsaved", std::make_pair(fs::path(), Signature{"crash", "no artifact saved", "", false}));
  st.findings = static_cast<int>(distinct.size());
  int written = 0;
  for (auto& [key, entry] : distinct) {
    auto& [file, sig] = entry;
    if (file.empty() || known.count(key) != 0) {
      std::printf("  [%s] known finding: %s\n", t.name.c_str(), key.c_str());
      continue;
    }
    if (written >= 10) break;
    fs::create_directories(regressions);
    const fs::path minimised = work / ("min-" + file.filename().string());
    const int budget = std::max(10, std::min(60, o.seconds));
    run_lines(kSanitizerEnv + quote(t.binary) + " -minimize_crash=1 -timeout=10 -rss_limit_mb=2048 -max_total_time=" +
                  std::to_string(budget) + " -exact_artifact_path=" + quote(minimised.string()) + " " +
                  quote(file.string()),
              [](const std::string&) {});
    fs::path keep = fs::exists(minimised) && fs::file_size(minimised) > 0 ? minimised : file;
    if (keep == minimised && !signature_of(t.binary, minimised, sig.kind).reproduced) keep = file;
    int hs = 0;
    std::string sha = run_capture("sha1sum " + quote(keep.string()) + " | cut -c1-16", &hs);
    sha.erase(std::remove(sha.begin(), sha.end(), '\n'), sha.end());
    const std::string base = sig.kind + "-" + sha;
    std::error_code copy_ec;
    fs::create_directories(regressions, copy_ec);
    fs::copy_file(keep, regressions / base, fs::copy_options::overwrite_existing, copy_ec);
    if (copy_ec) {
      std::printf("  [%s] could not write the reproducer %s: %s (kept in %s)\n", t.name.c_str(),
                  (regressions / base).string().c_str(), copy_ec.message().c_str(), keep.string().c_str());
      continue;
    }
    std::ofstream summary(regressions / (base + ".txt"));
    summary << today() << " " << sig.kind << ", " << fs::file_size(keep) << " bytes (minimised from "
            << fs::file_size(file) << "): " << sig.summary << (sig.frames.empty() ? "" : " at " + sig.frames)
            << "; found by axisproof fuzz --time " << o.seconds << "; signature: " << key << "\n";
    ++written;
    std::printf("  [%s] NEW finding -> %s\n      %s\n", t.name.c_str(), (regressions / base).string().c_str(),
                key.c_str());
  }
  st.new_findings = written;
  return st;
}

}  // namespace ap::cli::fuzz_engine
