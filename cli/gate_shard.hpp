#pragma once
// Sharding the release gate (docs/ci.md "Shards"): the parts of every stage that can be split
// (ctest tests, end-to-end tests, fuzz replays and runs, mutants, proof obligations, QEMU
// scenarios, and the one-piece m4 and bench stages), the seconds the last recorded run gave
// each (ci/gate-times/<profile>/times.tsv), and the shard that runs each. Every shard of one commit
// lists the same parts from the same build and reads the same times file, so every shard
// computes the same plan without talking to the others; the join checks that they did
// (gate_join.cpp).
#include "gate.hpp"
#include "gate_plan.hpp"

#include <map>
#include <string>
#include <vector>

namespace ap::cli::gate_stages {

struct Shard {
  int index = 0;  // 1..count
  int count = 0;  // 0: not sharded
  bool on() const { return count > 0; }
};
extern Shard g_shard;

// "I/N" with 1 <= I <= N <= 64.
bool parse_shard(const std::string& text, Shard* out, std::string* error);

extern Plan g_plan;

// The parts of the profile's gate, listed from the asan build, the mutants and the profile.
std::map<std::string, std::vector<std::string>> list_parts(const std::string& times_file);

// The times file the plan reads by default: ci/gate-times/<profile>/times.tsv.
std::string default_times_file();

// This shard's parts of `stage` among `all`, in their order (all of them when not sharded).
std::vector<std::string> my_parts(const std::string& stage, const std::vector<std::string>& all);
bool my_part(const std::string& stage, const std::string& name);
int shard_of(const std::string& stage, const std::string& name);  // 0 when not in the plan

// The QEMU scenario the stage runs twice (its part "repeat:NAME" in the plan).
std::string repeat_scenario();

// ctest's names of the tests with these labels (and the profile's), without `exclude` (-E).
std::vector<std::string> ctest_names(const std::string& labels, const std::string& exclude = "");
// A ctest -R regex that matches exactly these names.
std::string exact_regex(const std::vector<std::string>& names);
// The tests of a ctest --output-junit file: name, passed/failed/..., seconds.
std::vector<gate::Item> read_ctest_junit(const std::string& file);

// gate_dir()/result.json (the join's input) and times.tsv (the next plan's input).
void write_result(const gate::Run& run, const std::string& file);
void write_times(const gate::Run& run, const std::string& file);
// The slowest build targets (from <build>/.ninja_log) and tests (from the run's items), for the report.
void time_tables(gate::Run& run, const std::string& build);

}  // namespace ap::cli::gate_stages
