#pragma once
// The fuzzing engine driver shared by `axisproof fuzz` and the gate's fuzz smoke stage
// (implemented in cmd_fuzz.cpp, one target's run in fuzz_run.cpp).
#include <string>
#include <string_view>
#include <vector>

namespace ap::cli {

// One line of <build>/fuzz_targets.txt (written by ap_add_fuzz_target at configure time).
struct FuzzTarget {
  std::string name;
  std::string group;   // its folder's name: the dictionary is <data>/dict/<name or group>.dict
  std::string binary;  // libFuzzer binary, "-" outside the fuzz preset
  std::string replay;  // plain replay driver
  std::string profile; // the firmware profile it belongs to (docs/profiles.md)
  std::string data;    // its profile's fuzz folder: corpus/<name>, regressions/<name>, dict/
};

// Reads <build_dir>/fuzz_targets.txt, keeping the targets of one profile (its fifth column,
// AP_PROFILE); empty when the file is missing or lists none of them.
std::vector<FuzzTarget> read_fuzz_targets(const std::string& build_dir, std::string_view profile);

struct FuzzOptions {
  std::string profile;               // only this profile's targets (set by --profile)
  std::vector<std::string> targets;  // empty: every target of the profile
  int seconds = 60;                  // per target
  int jobs = 2;                      // libFuzzer -fork=N
  // false: new inputs are merged into <data>/corpus/<t> and reproducers go to
  // <data>/regressions/<t>; true: both stay under out/fuzz/<t>/ (the gate must not edit the tree).
  bool no_save = false;
};

struct FuzzStats {
  std::string target;
  long long executions = 0;
  long long exec_per_s = 0;
  long long corpus_files = 0;  // <data>/corpus/<t> after the merge
  long long coverage = 0;      // libFuzzer "cov:" (edges)
  int new_inputs = 0;          // added to the corpus by the merge
  int findings = 0;            // distinct crash signatures (new and already known)
  int new_findings = 0;        // reproducers written this run
  double seconds = 0;
  bool ran = false;            // false when the target could not be run at all
  std::string note;
};

// Builds the fuzz preset's fuzz targets, runs each, merges, minimises findings. Writes
// out/fuzz/<t>/stats.txt per target. Returns the per-target stats; *ok is false when
// something could not run (build failure, unknown target, no targets).
std::vector<FuzzStats> run_fuzz(const FuzzOptions& options, bool* ok);

namespace fuzz_engine {
// One target's run for run_fuzz (fuzz_run.cpp): fuzzes, merges, minimises its findings.
FuzzStats fuzz_one(const FuzzTarget& t, const FuzzOptions& o);
}  // namespace fuzz_engine

}  // namespace ap::cli
