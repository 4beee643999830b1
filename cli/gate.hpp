#pragma once
// The release gate's data and its report writers (cmd_gate.cpp runs the stages,
// gate_report.cpp writes the verdict table, JUnit XML, out/gate/report.{md,html} and the
// release manifest).
#include <map>
#include <string>
#include <vector>

namespace ap::cli::gate {

enum class Result { Pass, Fail, NotRun };
const char* to_string(Result r);

struct Outcome {
  Result result = Result::NotRun;
  std::string key;  // the stage's key figure, or why it failed / did not run
};

struct Row {
  std::string id;  // the stage's id (--skip), the key of its items in Run::items
  std::string stage;
  Outcome outcome;
  double seconds = 0;
  std::string log;  // path of the stage's log, relative to the source dir ("" if none)
};

// Sections the stages leave for the report (plain data, already formatted where noted).
struct Details {
  std::vector<std::vector<std::string>> proofs;     // obligation, result, seconds, method
  std::vector<std::vector<std::string>> fuzz;       // target, executions, exec/s, corpus, cov, findings
  std::vector<std::vector<std::string>> mutants;    // mutant, models, result, seconds
  std::string mutation_summary;                     // "25 of 25 killed ..."
  std::vector<std::vector<std::string>> coverage;   // file, lines, line %, branches, branch %
  std::string coverage_summary;                     // "lines 95.1 %, branches 91.2 % ..."
  std::string m4_size_md;                           // out/release/m4-size.md contents
  std::vector<std::string> plots;                   // SVG paths relative to out/gate/
  std::vector<std::vector<std::string>> build_times;  // target, steps, seconds, share: where the asan build's time went
  std::vector<std::vector<std::string>> test_times;   // test, stage, seconds, share: the slowest tests
};

// One part of a stage that can be split over shards (a ctest test, a mutant, an obligation, a
// fuzz target's run, a QEMU scenario): what it gave and how long it took. A shard's result
// lists these so the join can check that every part ran exactly once, and the next run's
// shards are balanced by these times (docs/ci.md).
struct Item {
  std::string name;
  std::string result;  // the stage's own word: passed/failed, PROVED, killed by ..., SURVIVED
  bool pass = false;
  double seconds = 0;
};

struct Run {
  std::vector<Row> rows;
  std::map<std::string, std::vector<Item>> items;  // stage id -> its parts, in the order they ran
  Details details;
  bool pass = false;
  double seconds = 0;
  std::string version, git_hash, date;
  std::string profile;  // the firmware profile judged (docs/profiles.md)
  std::string size_tag = "m4";  // its release libraries (out/release/<tag>/) and size table
  std::string shard = "1/1";    // I/N of a sharded gate; "joined N" for the join's run
};

void print_table(const Run& run);
bool write_junit(const Run& run, const std::string& file);
void write_reports(const Run& run, const std::string& dir);       // report.md, report.html
void write_manifest(const Run& run, const std::string& release);  // manifest.json, MANIFEST.md

}  // namespace ap::cli::gate
