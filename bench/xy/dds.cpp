// DDS test bus latency (docs/sim.md): lockstep round trips PcEndpoint::step() -> board echo,
// two participants in one process (threads) and in two processes, beside `ddsperf` ping-pong on
// the same machine with the same loopback configuration. docs/dds.md lists the numbers.
//
// Counters: half_rtt_us (ddsperf reports half the round trip, so this is the comparable figure),
// frames_per_s (lockstep steps per wall second), sim_over_wall (virtual time per wall time at the
// thesis' 100 ms command period), ratio_vs_ddsperf (two-process half RTT / ddsperf mean).
#include <benchmark/benchmark.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "pc/dds/bus.hpp"
#include "pc/dds/domain.hpp"

extern char** environ;

namespace {

using namespace std::chrono_literals;
namespace dds = ap::dds;

constexpr std::uint32_t kFirstDomain = 200;
constexpr std::uint32_t kLastDomain = 230;
constexpr std::uint64_t kPeriodUs = 100'000;
const std::vector<std::uint8_t> kFrame(24, '0');   // about one command string

double g_two_process_half_rtt_us = 0.0;

int board_loop(std::uint32_t domain) {
  dds::BoardEndpoint b(domain, 0);
  if (!b.wait_matched(20s)) return 2;
  dds::Telemetry t;
  for (;;) {
    auto c = b.take_command(20s);
    if (!c) return 3;
    t.vtime_us = c->vtime_us;
    b.echo(*c, c->bytes, t);
    if ((c->flags & dds::kFlagShutdown) != 0U) return 0;
  }
}

// The child process of the two-process benchmark: this binary re-executed with the variable set.
const int g_child = [] {
  if (const char* d = std::getenv("AP_DDS_BENCH_BOARD")) {
    std::_Exit(board_loop(static_cast<std::uint32_t>(std::strtoul(d, nullptr, 10))));
  }
  return 0;
}();

void run_pc(benchmark::State& state, dds::PcEndpoint& pc) {
  if (!pc.wait_matched(20s)) {
    state.SkipWithError("board did not match");
    return;
  }
  std::uint64_t vt = 0;
  for (int i = 0; i < 200; ++i) pc.step(kFrame, vt += kPeriodUs);   // warm-up
  const auto t0 = std::chrono::steady_clock::now();
  std::int64_t n = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(pc.step(kFrame, vt += kPeriodUs));
    ++n;
  }
  const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  const double rtt = us / static_cast<double>(std::max<std::int64_t>(n, 1));
  state.counters["half_rtt_us"] = rtt / 2.0;
  state.counters["frames_per_s"] = 1e6 / rtt;
  state.counters["sim_over_wall"] = static_cast<double>(kPeriodUs) / rtt;
  pc.send(kFrame, vt + kPeriodUs, dds::kFlagShutdown);
  (void)pc.take_echo(5s);
}

void BM_DdsLockstepTwoThreads(benchmark::State& state) {
  dds::use_loopback_config();
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  int rc = -1;
  std::thread board([&] { rc = board_loop(lease.id()); });
  {
    dds::PcEndpoint pc(lease.id(), 0);
    run_pc(state, pc);
  }
  board.join();
  if (rc != 0) state.SkipWithError("board thread failed");
}
BENCHMARK(BM_DdsLockstepTwoThreads)->Unit(benchmark::kMicrosecond)->MinTime(2.0)->UseRealTime();

void BM_DdsLockstepTwoProcesses(benchmark::State& state) {
  dds::use_loopback_config();
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  std::vector<std::string> env_store;
  for (char** e = environ; *e != nullptr; ++e) env_store.emplace_back(*e);
  env_store.push_back("AP_DDS_BENCH_BOARD=" + std::to_string(lease.id()));
  std::vector<char*> envp;
  for (auto& s : env_store) envp.push_back(s.data());
  envp.push_back(nullptr);
  char self[] = "/proc/self/exe";
  char* argv[] = {self, nullptr};
  pid_t child = 0;
  if (posix_spawn(&child, "/proc/self/exe", nullptr, nullptr, argv, envp.data()) != 0) {
    state.SkipWithError("posix_spawn failed");
    return;
  }
  {
    dds::PcEndpoint pc(lease.id(), 0);
    run_pc(state, pc);
  }
  int status = 0;
  waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) state.SkipWithError("board process failed");
  g_two_process_half_rtt_us = state.counters["half_rtt_us"];
}
BENCHMARK(BM_DdsLockstepTwoProcesses)->Unit(benchmark::kMicrosecond)->MinTime(2.0)->UseRealTime();

// ddsperf ping/pong, 2 processes, same loopback config, its own domain, 4 s; the figure is the
// median of its per-second "mean" latencies after the first second (discovery).
void BM_DdsperfPingPong(benchmark::State& state) {
  dds::use_loopback_config();
  const auto lease = dds::DomainLease::claim(kFirstDomain, kLastDomain);
  const std::string id = std::to_string(lease.id());
  const std::string env = "CYCLONEDDS_URI='" + dds::loopback_config_uri() + "' ";
  std::vector<double> means;
  for (auto _ : state) {
    const std::string pong = env + "ddsperf -i " + id + " -D 5 pong >/dev/null 2>&1 &";
    if (std::system(pong.c_str()) != 0) {
      state.SkipWithError("cannot start ddsperf pong");
      return;
    }
    std::this_thread::sleep_for(300ms);
    const std::string ping = env + "ddsperf -i " + id + " -D 4 ping 2>&1";
    FILE* p = popen(ping.c_str(), "r");
    if (p == nullptr) {
      state.SkipWithError("cannot run ddsperf ping");
      return;
    }
    char line[512];
    int second = 0;
    while (std::fgets(line, sizeof line, p) != nullptr) {
      const char* m = std::strstr(line, " mean ");
      if (m != nullptr && std::strstr(line, "size") != nullptr && ++second > 1) {
        means.push_back(std::strtod(m + 6, nullptr));
      }
    }
    pclose(p);
  }
  if (means.empty()) {
    state.SkipWithError("no ddsperf latency lines (is ddsperf installed?)");
    return;
  }
  std::sort(means.begin(), means.end());
  const double ddsperf = means[means.size() / 2];
  state.counters["ddsperf_half_rtt_us"] = ddsperf;
  if (g_two_process_half_rtt_us > 0) {
    state.counters["ratio_vs_ddsperf"] = g_two_process_half_rtt_us / ddsperf;
  }
}
BENCHMARK(BM_DdsperfPingPong)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
