#pragma once
// The release gate's stages and the helpers they share. cmd_gate.cpp grew past what one file
// reads well, so the stages are split by concern (docs/architecture.md, "The release gate"):
//   gate_build_stages.cpp    the builds, the ctest stages and the helpers every stage uses
//   gate_check_stages.cpp    proofs, fuzz smoke, end-to-end scenarios
//   gate_release_stages.cpp  mutation, coverage, cortex-m4, QEMU, bench
// and cmd_gate.cpp keeps the command, its options and the stage table. Private to cli/: a
// namespace of its own, so these names cannot meet another command's file-local helpers in
// the unity build (cli/CMakeLists.txt).
#include "gate.hpp"
#include "profile.hpp"

#include <CLI/CLI.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <string>

namespace ap::cli::gate_stages {

using gate::Outcome;
using gate::Result;

// Set by `axisproof gate` (cmd_gate.cpp) from its options.
extern std::string g_out;           // --out: reports go to g_out/gate, the release to g_out/release
extern const Profile* g_profile;    // --profile: the profile the gate judges
extern int fuzz_seconds;            // --fuzz-time: seconds per target in the fuzz smoke
extern std::map<std::string, bool> built_ok;  // preset -> its build stage passed

std::string slurp(const std::string& path);
std::string trim(std::string s);
// Runs a shell command in the source dir, output (stdout + stderr) to `log`; lines matching
// `echo` are shown indented, as progress. Returns the exit status.
int run_logged(const std::string& command, const std::string& log, const std::string& echo = "");
std::string gate_dir();     // g_out/gate
std::string release_dir();  // g_out/release
std::string self_exe();
std::string profile_labels();  // ctest -L regex: the profile's label or harness
bool asan_shared();            // build/asan has coverage and the libFuzzer binaries
int build_jobs();
int count_tests(const std::string& preset, const std::string& labels, const std::string& exclude = "");
std::string profile_dir();  // where the asan build's tests write coverage profiles
std::string fuzz_replay_exclude();  // the fuzz tests the fuzz smoke does not replay (ctest -E)
std::string shard_text();           // "I/N" of this shard ("1/1" when not sharded)
// Runs job(0) .. job(count - 1) on up to build_jobs() threads at once.
void run_parallel(std::size_t count, const std::function<void(std::size_t)>& job);

// The stages, in the gate's order.
Outcome build_stage(const std::string& preset, const std::string& log, const std::string& target = "");
Outcome ctest_stage(gate::Run& run, const std::string& id, const std::string& labels, const std::string& junit,
                    const std::string& log, const std::string& exclude = "");
Outcome proofs_stage(gate::Run& run, const std::string& log);
Outcome fuzz_stage(gate::Run& run, const std::string& log);
Outcome e2e_stage(gate::Run& run, const std::string& log);
Outcome mutation_stage(gate::Run& run, const std::string& log);
Outcome coverage_stage(gate::Run& run, const std::string& log);
// The coverage report over the profiles in `profiles` (the join gives all shards' profiles).
Outcome coverage_report(gate::Run& run, const std::string& log, const std::string& profiles);
Outcome m4_stage(gate::Run& run, const std::string& log);
Outcome qemu_stage(gate::Run& run, const std::string& log);
Outcome bench_stage(gate::Run& run, const std::string& log);

// `axisproof gate join DIR...` (gate_join.cpp), a subcommand of `gate`.
CLI::App* add_gate_join(CLI::App* gate);

}  // namespace ap::cli::gate_stages
