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

void write_stats(const fs::path& file, const FuzzStats& s) {
  std::ofstream out(file);
  out << "target=" << s.target << "\nexecutions=" << s.executions << "\nexec_per_s=" << s.exec_per_s
      << "\ncorpus_files=" << s.corpus_files << "\ncoverage=" << s.coverage << "\nnew_inputs=" << s.new_inputs
      << "\nfindings=" << s.findings << "\nnew_findings=" << s.new_findings << "\nseconds=" << s.seconds
      << "\nnote=" << s.note << "\n";
}

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
    FuzzStats st = it == all.end() ? FuzzStats{} : fuzz_one(*it, o);
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
