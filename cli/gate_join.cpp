// `axisproof gate join DIR...`: the verdict of a sharded gate. Reads each shard's
// DIR/gate/result.json (gate_shard.cpp), checks that the shards are one gate (same profile,
// commit and plan; every shard 1..N exactly once; each ran exactly the parts the plan gave it),
// measures the coverage of all shards' profiles together, and writes the verdict table,
// report.md/html, JUnit, the release manifest, result.json and times.tsv the single-machine
// gate writes. Any shard that is missing, given twice, from another commit or failed makes the
// verdict FAIL with the reason (docs/ci.md "Shards").
#include "cli.hpp"
#include "gate_shard.hpp"
#include "gate_stages.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace ap::cli::gate_stages {
namespace {

using nlohmann::json;

struct ShardResult {
  std::string dir;
  json j;
  int index = 0, count = 0;
};

gate::Result result_of(const std::string& s) {
  if (s == "PASS") return gate::Result::Pass;
  if (s == "FAIL") return gate::Result::Fail;
  return gate::Result::NotRun;
}

std::vector<std::vector<std::string>> table_of(const json& j) {
  std::vector<std::vector<std::string>> t;
  if (j.is_array()) {
    for (const auto& row : j) t.push_back(row.get<std::vector<std::string>>());
  }
  return t;
}

int shard_of_json(const ShardResult& r, const std::string& stage, const std::string& name) {
  for (const auto& p : r.j["plan"]["parts"]) {
    if (p.at(0).get<std::string>() == stage && p.at(1).get<std::string>() == name) return p.at(2).get<int>();
  }
  return 0;
}

// The merged key figure of a stage that was split, from its parts.
std::string joined_key(const std::string& id, const std::vector<gate::Item>& items, int shards) {
  const auto failed = std::count_if(items.begin(), items.end(), [](const gate::Item& i) { return !i.pass; });
  const std::string n = std::to_string(items.size());
  const std::string f = std::to_string(failed);
  const std::string over = " (" + std::to_string(shards) + " shards)";
  if (id == "tests" || id == "e2e") return n + " tests, " + f + " failed" + over;
  if (id == "proofs") return n + " obligations, " + std::to_string(items.size() - static_cast<std::size_t>(failed)) + " proved" + over;
  if (id == "mutation") return std::to_string(items.size() - static_cast<std::size_t>(failed)) + "/" + n + " killed" + over;
  if (id == "fuzz") {
    const auto targets = std::count_if(items.begin(), items.end(), [](const gate::Item& i) { return i.name.rfind("target:", 0) == 0; });
    const auto findings = std::count_if(items.begin(), items.end(),
                                        [](const gate::Item& i) { return i.name.rfind("target:", 0) == 0 && !i.pass; });
    return std::to_string(items.size() - static_cast<std::size_t>(targets)) + " replay tests; " + std::to_string(targets) +
           " targets, " + std::to_string(findings) + " findings" + over;
  }
  if (id == "qemu") {
    const auto scenarios = std::count_if(items.begin(), items.end(), [](const gate::Item& i) { return i.name.rfind("repeat:", 0) != 0; });
    const auto ok = std::count_if(items.begin(), items.end(), [](const gate::Item& i) { return i.name.rfind("repeat:", 0) != 0 && i.pass; });
    std::string key = std::to_string(ok) + "/" + std::to_string(scenarios) + " scenarios PASS on the image, traces equal to the host's";
    for (const auto& i : items) {
      if (i.name.rfind("repeat:", 0) == 0) key += ", " + i.name.substr(7) + (i.pass ? " repeatable" : " NOT repeatable");
    }
    return key + over;
  }
  return n + " parts, " + f + " failed" + over;
}

int join(const std::vector<std::string>& dirs, const std::string& out_root, const std::string& junit) {
  const auto start = std::chrono::steady_clock::now();
  const std::string src = source_dir();
  std::vector<std::string> problems;
  std::vector<ShardResult> shards;
  for (const auto& d : dirs) {
    std::string file = d + "/gate/result.json";
    if (!fs::exists(file)) file = d + "/result.json";
    std::ifstream in(file);
    if (!in) {
      problems.push_back(d + ": no gate/result.json (the shard did not finish, or this is not a shard's --out folder)");
      continue;
    }
    ShardResult r;
    r.dir = d;
    try {
      in >> r.j;
      r.index = r.j.at("shard").at(0).get<int>();
      r.count = r.j.at("shard").at(1).get<int>();
      if (r.j.at("format").get<int>() != 1) throw std::runtime_error("unknown format");
    } catch (const std::exception& e) {
      problems.push_back(file + ": not a gate result (" + e.what() + ")");
      continue;
    }
    shards.push_back(std::move(r));
  }
  if (shards.empty()) {
    for (const auto& p : problems) std::fprintf(stderr, "axisproof gate join: %s\n", p.c_str());
    std::fprintf(stderr, "axisproof gate join: no shard results: FAIL\n");
    return 1;
  }
  const ShardResult& first = shards.front();
  const int count = first.count;
  const std::string profile_name = first.j.value("profile", "");
  for (const auto& s : shards) {
    const std::string who = "shard " + std::to_string(s.index) + "/" + std::to_string(s.count) + " (" + s.dir + ")";
    if (s.j.value("profile", "") != profile_name) problems.push_back(who + " judged profile " + s.j.value("profile", "") + ", not " + profile_name);
    if (s.j.value("commit", "") != first.j.value("commit", "")) {
      problems.push_back(who + " is from another commit: " + s.j.value("commit", "") + ", not " + first.j.value("commit", ""));
    }
    if (s.count != count) problems.push_back(who + " is one of " + std::to_string(s.count) + " shards, not " + std::to_string(count));
    if (s.j["plan"].value("digest", "") != first.j["plan"].value("digest", "")) {
      problems.push_back(who + " followed another plan (parts or times differ): " + s.j["plan"].value("digest", "") + ", not " +
                         first.j["plan"].value("digest", ""));
    }
  }
  for (int i = 1; i <= count; ++i) {
    std::vector<std::string> given;
    for (const auto& s : shards) {
      if (s.index == i) given.push_back(s.dir);
    }
    const std::string which = "shard " + std::to_string(i) + "/" + std::to_string(count);
    if (given.empty()) problems.push_back(which + " missing");
    if (given.size() > 1) {
      std::string list;
      for (const auto& g : given) list += (list.empty() ? "" : ", ") + g;
      problems.push_back(which + " given " + std::to_string(given.size()) + " times (" + list + ")");
    }
  }
  g_profile = find_profile(profile_name);
  if (g_profile == nullptr) {
    std::fprintf(stderr, "axisproof gate join: the results judge profile '%s', which this axisproof does not have: FAIL\n", profile_name.c_str());
    return 1;
  }
  // Every planned part ran once, in the shard the plan gave it.
  std::map<std::pair<std::string, std::string>, int> planned;
  for (const auto& p : first.j["plan"]["parts"]) planned[{p.at(0).get<std::string>(), p.at(1).get<std::string>()}] = p.at(2).get<int>();
  std::map<std::pair<std::string, std::string>, std::vector<int>> ran;
  gate::Run run;
  std::set<int> seen;
  for (const auto& s : shards) {
    if (!seen.insert(s.index).second) continue;  // a duplicate is reported above; its parts once
    for (const auto& [stage, list] : s.j["items"].items()) {
      for (const auto& i : list) {
        gate::Item item{i.value("name", ""), i.value("result", ""), i.value("pass", false), i.value("seconds", 0.0)};
        ran[{stage, item.name}].push_back(s.index);
        run.items[stage].push_back(item);
      }
    }
  }
  // A stage's parts go missing when the stage did not run in a shard (its build failed): the
  // stage's own FAIL or NOT RUN says why, so only parts of stages that ran are counted here.
  std::map<std::string, int> missing;
  for (const auto& [part, shard] : planned) {
    const auto it = ran.find(part);
    if (it == ran.end()) {
      ++missing[part.first];
    } else if (it->second.size() != 1 || it->second.front() != shard) {
      problems.push_back(part.first + " part " + part.second + " ran in shard(s) " + std::to_string(it->second.front()) +
                         (it->second.size() > 1 ? " and others" : "") + ", the plan gave it to shard " + std::to_string(shard));
    }
  }
  for (const auto& [part, who] : ran) {
    if (planned.count(part) == 0) problems.push_back(part.first + " part " + part.second + " is not in the plan");
  }
  for (auto& [stage, list] : run.items) {
    std::sort(list.begin(), list.end(), [](const gate::Item& a, const gate::Item& b) { return a.name < b.name; });
  }

  std::error_code ec;
  g_out = out_root.empty() ? src + "/out" : fs::absolute(out_root).string();
  fs::remove_all(gate_dir(), ec);
  fs::remove_all(release_dir(), ec);
  fs::create_directories(gate_dir() + "/logs");
  run.profile = first.j.value("profile_title", profile_name);
  run.size_tag = std::string(g_profile->size_tag);
  run.version = first.j.value("version", "");
  run.git_hash = first.j.value("commit", "");
  run.date = first.j.value("date", "");
  run.shard = "joined " + std::to_string(count) + " shards (stage times summed over the shards; total: the longest shard plus the join)";

  // The stages in the gate's order, merged.
  double longest = 0;
  for (const auto& s : shards) longest = std::max(longest, s.j.value("seconds", 0.0));
  std::vector<std::string> order;
  for (const auto& s : shards) {
    for (const auto& r : s.j["rows"]) {
      const std::string id = r.value("id", "");
      if (std::find(order.begin(), order.end(), id) == order.end()) order.push_back(id);
    }
  }
  std::string profdata_dir = gate_dir() + "/coverage-profiles";
  fs::create_directories(profdata_dir);
  int profiles = 0;
  for (const auto& s : shards) {
    const fs::path p = fs::absolute(s.dir + "/gate/coverage.profdata");
    if (fs::exists(p)) {
      fs::create_symlink(p, profdata_dir + "/shard-" + std::to_string(s.index) + ".profdata", ec);
      ++profiles;
    }
  }
  for (const auto& id : order) {
    gate::Row row;
    row.id = id;
    std::vector<std::string> not_pass;
    gate::Result result = gate::Result::Pass;
    std::string owner_key;
    for (const auto& s : shards) {
      for (const auto& r : s.j["rows"]) {
        if (r.value("id", "") != id) continue;
        row.stage = r.value("stage", id);
        row.seconds += r.value("seconds", 0.0);
        const gate::Result res = result_of(r.value("result", ""));
        if (res == gate::Result::Fail) result = gate::Result::Fail;
        else if (res == gate::Result::NotRun && result == gate::Result::Pass) result = gate::Result::NotRun;
        if (res != gate::Result::Pass) {
          not_pass.push_back("shard " + std::to_string(s.index) + ": " + r.value("result", "") + " " + r.value("key", ""));
        }
        const int owner = id == "m4" || id == "bench" ? shard_of_json(first, id, id) : 1;
        if (s.index == owner) owner_key = r.value("key", "");
      }
    }
    if (id == "coverage") {
      // Measured here, over every shard's profiles.
      const auto t0 = std::chrono::steady_clock::now();
      gate::Outcome o;
      if (static_cast<int>(shards.size()) != count || profiles != count) {
        o = {gate::Result::NotRun, std::to_string(profiles) + " of " + std::to_string(count) + " shards left coverage profiles"};
      } else {
        o = coverage_report(run, gate_dir() + "/logs/coverage.log", profdata_dir);
      }
      row.outcome = o;
      row.seconds = seconds_since(t0);
      row.log = fs::relative(gate_dir() + "/logs/coverage.log", src, ec).string();
      if (result != gate::Result::Pass && o.result == gate::Result::Pass) row.outcome.result = result;
    } else {
      const auto it = run.items.find(id);
      const bool split = it != run.items.end() && id != "m4" && id != "bench";
      row.outcome = {result, split ? joined_key(id, it->second, count) : owner_key};
      if (id == "build-dev" || id == "build-asan") row.outcome.key = owner_key + " (shard 1; every shard builds the same)";
      if (missing.count(id) != 0 && result == gate::Result::Pass) {
        row.outcome = {gate::Result::Fail, std::to_string(missing[id]) + " planned parts did not run"};
      }
    }
    if (row.outcome.result != gate::Result::Pass && !not_pass.empty()) {
      row.outcome.key.clear();
      for (std::size_t i = 0; i < not_pass.size() && i < 3; ++i) row.outcome.key += (i ? "; " : "") + not_pass[i];
      if (not_pass.size() > 3) row.outcome.key += "; ...";
    }
    run.rows.push_back(row);
  }
  if (!problems.empty()) {
    std::string key;
    for (std::size_t i = 0; i < problems.size() && i < 4; ++i) key += (i ? "; " : "") + problems[i];
    if (problems.size() > 4) key += "; and " + std::to_string(problems.size() - 4) + " more (see logs/join.log)";
    run.rows.insert(run.rows.begin(), gate::Row{"shards", "shards", {gate::Result::Fail, key}, 0, ""});
    std::ofstream log(gate_dir() + "/logs/join.log");
    for (const auto& p : problems) log << p << "\n";
  }
  // The report's sections from the shards: each part once.
  for (const auto& s : shards) {
    const auto& d = s.j["details"];
    for (auto& row : table_of(d["proofs"])) run.details.proofs.push_back(row);
    for (auto& row : table_of(d["fuzz"])) run.details.fuzz.push_back(row);
    for (auto& row : table_of(d["mutants"])) run.details.mutants.push_back(row);
    if (s.index == shard_of_json(first, "m4", "m4")) run.details.m4_size_md = d.value("m4_size_md", "");
    if (s.index == 1) run.details.build_times = table_of(d["build_times"]);
  }
  std::sort(run.details.proofs.begin(), run.details.proofs.end());
  std::sort(run.details.fuzz.begin(), run.details.fuzz.end());
  std::sort(run.details.mutants.begin(), run.details.mutants.end());
  const auto killed = std::count_if(run.details.mutants.begin(), run.details.mutants.end(),
                                    [](const std::vector<std::string>& m) { return m.size() > 2 && m[2].rfind("killed", 0) == 0; });
  run.details.mutation_summary = std::to_string(killed) + " of " + std::to_string(run.details.mutants.size()) +
                                 " mutants killed, judged by " + std::to_string(count) + " shards";
  {
    const auto build_times = run.details.build_times;
    time_tables(run, build_dir("asan"));
    run.details.build_times = build_times;  // shard 1's build, not this machine's
  }
  // The release artifact is the one the m4 stage's shard built.
  for (const auto& s : shards) {
    if (s.index == shard_of_json(first, "m4", "m4") && fs::is_directory(s.dir + "/release")) {
      fs::copy(s.dir + "/release", release_dir(), fs::copy_options::recursive | fs::copy_options::overwrite_existing, ec);
    }
  }
  run.pass = std::all_of(run.rows.begin(), run.rows.end(), [](const gate::Row& r) { return r.outcome.result == gate::Result::Pass; });
  run.seconds = longest + seconds_since(start);
  gate::print_table(run);
  gate::write_reports(run, gate_dir());
  gate::write_manifest(run, release_dir());
  g_shard = {};
  g_plan.parts.clear();
  for (const auto& [part, shard] : planned) g_plan.parts.push_back({part.first, part.second, 0, shard});
  g_plan.digest = first.j["plan"].value("digest", "");
  g_plan.times_file = first.j["plan"].value("times_file", "");
  write_result(run, gate_dir() + "/result.json");
  write_times(run, gate_dir() + "/times.tsv");
  if (!problems.empty()) {
    for (const auto& p : problems) std::fprintf(stderr, "axisproof gate join: %s\n", p.c_str());
  }
  const std::string shown = out_root.empty() ? "out" : g_out;
  std::printf("report: %s/gate/report.md, %s/gate/report.html; release artifact: %s/release/; parts' times: %s/gate/times.tsv\n",
              shown.c_str(), shown.c_str(), shown.c_str(), shown.c_str());
  if (!junit.empty()) {
    if (gate::write_junit(run, junit)) std::printf("JUnit XML: %s\n", junit.c_str());
    else std::fprintf(stderr, "axisproof gate join: cannot write %s\n", junit.c_str());
  }
  return run.pass ? 0 : 1;
}

}  // namespace

CLI::App* add_gate_join(CLI::App* gate) {
  auto* sub = gate->add_subcommand(
      "join", "Merge the results of N shards (`axisproof gate --shard I/N --out DIR`) into one verdict: FAIL when a shard is missing, "
              "given twice, from another commit or failed");
  static std::vector<std::string> dirs;
  static std::string out_root;
  static std::string junit;
  sub->add_option("DIR", dirs, "Each shard's --out folder (holding gate/result.json)")->required();
  sub->add_option("--out", out_root, "Write the joined reports to DIR/gate and the release artifact to DIR/release (default out/)");
  sub->add_option("--junit", junit, "Also write the verdict as JUnit XML to FILE");
  sub->final_callback([] { exit_status() = join(dirs, out_root, junit); });
  return sub;
}

}  // namespace ap::cli::gate_stages
