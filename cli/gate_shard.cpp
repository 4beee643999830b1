// Sharding the release gate: the parts of the splittable stages, the plan that deals them to
// shards by the last recorded times, and the files a run leaves for the join and for the next
// plan (result.json, times.tsv). docs/ci.md "Shards" says why the plan is computed by every
// shard alone and what the join checks.
#include "gate_shard.hpp"

#include "cli.hpp"
#include "fuzz_run.hpp"
#include "gate_stages.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli::gate_stages {

Shard g_shard;
Plan g_plan;

std::string shard_text() { return g_shard.on() ? std::to_string(g_shard.index) + "/" + std::to_string(g_shard.count) : "1/1"; }

// The ClusterFuzzLite build-script check builds a tree of its own; `axisproof test` runs it.
std::string fuzz_replay_exclude() { return "^fuzz\\.clusterfuzzlite_build_sh$"; }

bool parse_shard(const std::string& text, Shard* out, std::string* error) {
  const std::regex re(R"((\d{1,2})/(\d{1,2}))");
  std::smatch m;
  if (!std::regex_match(text, m, re)) {
    *error = "--shard takes I/N (e.g. 2/4), not '" + text + "'";
    return false;
  }
  const int i = std::stoi(m[1].str());
  const int n = std::stoi(m[2].str());
  if (n < 1 || n > 64 || i < 1 || i > n) {
    *error = "--shard I/N needs 1 <= I <= N <= 64, not " + text;
    return false;
  }
  *out = {i, n};
  return true;
}

int shard_of(const std::string& stage, const std::string& name) {
  for (const auto& p : g_plan.parts) {
    if (p.stage == stage && p.name == name) return p.shard;
  }
  return 0;
}

bool my_part(const std::string& stage, const std::string& name) {
  return !g_shard.on() || shard_of(stage, name) == g_shard.index;
}

std::vector<std::string> my_parts(const std::string& stage, const std::vector<std::string>& all) {
  std::vector<std::string> mine;
  for (const auto& n : all) {
    if (my_part(stage, n)) mine.push_back(n);
  }
  return mine;
}

std::string default_times_file() { return source_dir() + "/ci/gate-times/" + std::string(g_profile->name) + "/times.tsv"; }

std::string repeat_scenario() {
  for (const auto& p : g_plan.parts) {
    if (p.stage == "qemu" && p.name.rfind("repeat:", 0) == 0) return p.name.substr(7);
  }
  return "";
}

std::vector<std::string> ctest_names(const std::string& labels, const std::string& exclude) {
  int st = 0;
  const std::string out = run_capture("cd " + quote(source_dir()) + " && ctest --preset asan -N -L " + quote(labels) + " -L " +
                                          quote(profile_labels()) + (exclude.empty() ? "" : " -E " + quote(exclude)) +
                                          " 2>/dev/null",
                                      &st);
  // A parameterised GoogleTest's ctest name has spaces ("Suite/Test.Case/p  # GetParam() = 3").
  std::vector<std::string> names;
  std::istringstream in(out);
  std::string line;
  const std::regex re(R"(^\s*Test\s+#\d+: (.+)$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, re)) names.push_back(trim(m[1].str()));
  }
  return names;
}

std::string exact_regex(const std::vector<std::string>& names) {
  std::string re = "^(";
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i) re += "|";
    for (const char c : names[i]) {
      if (std::string(".[]()*+?^$|\\").find(c) != std::string::npos) re += '\\';
      re += c;
    }
  }
  return re + ")$";
}

std::vector<gate::Item> read_ctest_junit(const std::string& file) {
  std::vector<gate::Item> items;
  const std::string text = slurp(file);
  const std::regex tag(R"(<testcase\b([^>]*)>)");
  const auto attr = [](const std::string& attrs, const std::string& key) {
    std::smatch m;
    if (std::regex_search(attrs, m, std::regex("\\b" + key + "=\"([^\"]*)\""))) return m[1].str();
    return std::string();
  };
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tag); it != std::sregex_iterator(); ++it) {
    const std::string attrs = (*it)[1].str();
    gate::Item item;
    item.name = xml_unescape(attr(attrs, "name"));
    const std::string status = attr(attrs, "status");
    // A test that skipped itself (SKIP_RETURN_CODE / SKIP_REGULAR_EXPRESSION) is "notrun" with
    // a <skipped message="SKIP_..."> in its body; ctest does not count it as failed, nor does
    // the gate. Any other "notrun" (no executable, a failed fixture) is a failure.
    const auto body_end = text.find("</testcase>", static_cast<std::size_t>(it->position() + it->length()));
    const std::string body = text.substr(static_cast<std::size_t>(it->position() + it->length()),
                                         body_end == std::string::npos ? 0 : body_end - static_cast<std::size_t>(it->position() + it->length()));
    const bool skipped = status == "notrun" && body.find("<skipped message=\"SKIP_") != std::string::npos;
    item.pass = status == "run" || skipped;
    item.result = status == "run" ? "passed" : skipped ? "skipped" : status.empty() ? "unknown" : status;
    try {
      item.seconds = std::stod(attr(attrs, "time"));
    } catch (...) {
      item.seconds = 0;
    }
    items.push_back(item);
  }
  return items;
}

std::map<std::string, std::vector<std::string>> list_parts(const std::string& times_file) {
  std::map<std::string, std::vector<std::string>> parts;
  parts["tests"] = ctest_names("unit|property|proof", std::string(g_profile->registry_tests));
  parts["e2e"] = ctest_names("e2e");
  for (const auto& n : ctest_names("fuzz", fuzz_replay_exclude())) parts["fuzz"].push_back(n);
  for (const auto& t : read_fuzz_targets(build_dir("asan"), g_profile->name)) parts["fuzz"].push_back("target:" + t.name);
  int st = 0;
  const std::string mutants = run_capture("cd " + quote(source_dir()) + " && ci/mutate --list --profile " +
                                              std::string(g_profile->name) + ",harness 2>/dev/null",
                                          &st);
  std::istringstream in(mutants);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string name;
    if (row >> name) parts["mutation"].push_back(name);
  }
  if (g_profile->obligations != nullptr) {
    for (const auto& o : g_profile->obligations()) parts["proofs"].push_back(o.name);
  }
  for (const auto& s : g_profile->qemu_scenarios) parts["qemu"].push_back(std::string(s));
  // The scenario the QEMU stage runs twice: the shortest by the recorded times (the first
  // declared when there are none), chosen before the plan so that every shard agrees.
  if (!g_profile->qemu_scenarios.empty()) {
    const auto times = parse_times(times_file.empty() ? std::string() : slurp(times_file));
    std::string best(g_profile->qemu_scenarios.front());
    double best_s = -1;
    if (times.count("qemu") != 0) {
      for (const auto& s : g_profile->qemu_scenarios) {
        const auto it = times.at("qemu").find(std::string(s));
        if (it != times.at("qemu").end() && (best_s < 0 || it->second < best_s)) {
          best_s = it->second;
          best = std::string(s);
        }
      }
    }
    parts["qemu"].push_back("repeat:" + best);
  }
  parts["m4"] = {"m4"};
  parts["bench"] = {"bench"};
  for (auto& [stage, names] : parts) {
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
  }
  return parts;
}

namespace {

using nlohmann::json;

json items_json(const std::vector<gate::Item>& items) {
  json a = json::array();
  for (const auto& i : items) a.push_back({{"name", i.name}, {"result", i.result}, {"pass", i.pass}, {"seconds", i.seconds}});
  return a;
}

}  // namespace

void write_result(const gate::Run& run, const std::string& file) {
  json j;
  j["format"] = 1;
  j["profile"] = std::string(g_profile->name);
  j["profile_title"] = run.profile;
  j["commit"] = run.git_hash;
  j["version"] = run.version;
  j["date"] = run.date;
  j["shard"] = {g_shard.on() ? g_shard.index : 1, g_shard.on() ? g_shard.count : 1};
  j["pass"] = run.pass;
  j["seconds"] = run.seconds;
  j["plan"] = {{"digest", g_plan.digest}, {"times_file", g_plan.times_file}};
  json parts = json::array();
  for (const auto& p : g_plan.parts) parts.push_back({p.stage, p.name, p.shard, p.seconds});
  j["plan"]["parts"] = parts;
  json rows = json::array();
  for (const auto& r : run.rows) {
    rows.push_back({{"id", r.id}, {"stage", r.stage}, {"result", gate::to_string(r.outcome.result)}, {"key", r.outcome.key},
                    {"seconds", r.seconds}, {"log", r.log}});
  }
  j["rows"] = rows;
  json items = json::object();
  for (const auto& [stage, list] : run.items) items[stage] = items_json(list);
  j["items"] = items;
  const auto& d = run.details;
  j["details"] = {{"proofs", d.proofs},   {"fuzz", d.fuzz},
                  {"mutants", d.mutants}, {"mutation_summary", d.mutation_summary},
                  {"coverage", d.coverage}, {"coverage_summary", d.coverage_summary},
                  {"m4_size_md", d.m4_size_md}, {"plots", d.plots},
                  {"build_times", d.build_times}, {"test_times", d.test_times}};
  fs::create_directories(fs::path(file).parent_path());
  std::ofstream(file) << j.dump(1) << "\n";
}

void write_times(const gate::Run& run, const std::string& file) {
  std::ofstream out(file);
  out << "# stage\tpart\tseconds: what each part of the gate took (axisproof gate; docs/ci.md \"Shards\")\n";
  for (const auto& [stage, list] : run.items) {
    for (const auto& i : list) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f", i.seconds);
      out << stage << "\t" << i.name << "\t" << buf << "\n";
    }
  }
}

void time_tables(gate::Run& run, const std::string& build) {
  // .ninja_log: start ms, end ms, mtime, output, hash (version 5), one line per output, so a
  // step with several outputs (an object and its PCH, a custom command's files) logs several
  // lines with the same start, end and command hash: it is counted once. A step's target is the
  // folder before CMakeFiles/<target>.dir in one of its outputs, or the output itself for a link.
  std::ifstream in(build + "/.ninja_log");
  std::string line;
  std::map<std::string, std::pair<int, double>> per;  // target -> steps, seconds
  std::map<std::string, std::string> last;            // output -> its line (a rebuilt output logs twice)
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    std::string start, end, mtime, output, hash;
    if (!std::getline(row, start, '\t') || !std::getline(row, end, '\t') || !std::getline(row, mtime, '\t') ||
        !std::getline(row, output, '\t')) {
      continue;
    }
    std::getline(row, hash, '\t');
    last[output] = start + "\t" + end + "\t" + hash;
  }
  const std::regex obj(R"(CMakeFiles/([^/]+)\.dir/)");
  std::map<std::string, std::pair<std::string, double>> steps;  // start, end, hash -> target, seconds
  for (const auto& [output, step] : last) {
    const auto tab = step.find('\t');
    double secs = 0;
    try {
      secs = (std::stod(step.substr(tab + 1)) - std::stod(step.substr(0, tab))) / 1000.0;
    } catch (...) {
      continue;
    }
    std::smatch m;
    const bool in_target = std::regex_search(output, m, obj);
    auto [it, added] = steps.try_emplace(step, in_target ? m[1].str() : fs::path(output).filename().string(), secs);
    if (!added && in_target) it->second.first = m[1].str();
  }
  double total = 0;
  for (const auto& [step, target_secs] : steps) {
    per[target_secs.first].first += 1;
    per[target_secs.first].second += target_secs.second;
    total += target_secs.second;
  }
  std::vector<std::pair<std::string, std::pair<int, double>>> rows(per.begin(), per.end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.second > b.second.second; });
  char buf[64];
  run.details.build_times.clear();
  for (std::size_t i = 0; i < rows.size() && i < 20; ++i) {
    std::snprintf(buf, sizeof buf, "%.1f", rows[i].second.second);
    std::string secs = buf;
    std::snprintf(buf, sizeof buf, "%.1f %%", total > 0 ? 100.0 * rows[i].second.second / total : 0.0);
    run.details.build_times.push_back({rows[i].first, std::to_string(rows[i].second.first), secs, buf});
  }
  if (!rows.empty()) {
    std::snprintf(buf, sizeof buf, "%.1f", total);
    run.details.build_times.push_back({"(all " + std::to_string(rows.size()) + " targets, " + std::to_string(steps.size()) + " steps; CPU seconds)", "", buf, "100 %"});
  }
  std::vector<std::pair<std::string, gate::Item>> tests;
  std::map<std::string, double> stage_total;
  for (const auto& stage : {"tests", "e2e", "fuzz"}) {
    const auto it = run.items.find(stage);
    if (it == run.items.end()) continue;
    for (const auto& i : it->second) {
      if (i.name.rfind("target:", 0) == 0) continue;
      tests.emplace_back(stage, i);
      stage_total[stage] += i.seconds;
    }
  }
  std::sort(tests.begin(), tests.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  run.details.test_times.clear();
  for (std::size_t i = 0; i < tests.size() && i < 20; ++i) {
    std::snprintf(buf, sizeof buf, "%.2f", tests[i].second.seconds);
    std::string secs = buf;
    const double t = stage_total[tests[i].first];
    std::snprintf(buf, sizeof buf, "%.1f %%", t > 0 ? 100.0 * tests[i].second.seconds / t : 0.0);
    run.details.test_times.push_back({tests[i].second.name, tests[i].first, secs, buf});
  }
}

}  // namespace ap::cli::gate_stages
