// Axis core cost: nanoseconds per control tick (one step() call) and simulated STEP pulses
// per second of host time, for two axes moving back and forth at a high step rate.
#include <benchmark/benchmark.h>

#include <array>

#include "core/xy/axis/axis.hpp"

namespace {

using namespace ap::xy_axis;

Config bench_config() {
  Config c;
  c.v_start = 1000;
  c.v_slow = 20000;
  c.v_fast = 200'000;
  c.accel = 400'000;
  c.soft_min = 0;
  c.soft_max = 2'000'000;
  return c;
}

// ns per tick: a long absolute move ping-ponging between two targets (every phase is hit).
void BM_AxisTick(benchmark::State& st) {
  const Config c = bench_config();
  State s;
  s.homed = 1;
  Input in;
  bool up = true;
  for (auto _ : st) {
    if (s.phase == Phase::Stop) {
      in.cmd = Command{CmdKind::MoveAbs, 0, 1, up ? 1'500'000 : 100'000};
      up = !up;
    } else {
      in.cmd = Command{};
    }
    const StepResult r = step(s, in, c);
    s = r.state;
    benchmark::DoNotOptimize(s);
  }
  st.SetItemsProcessed(st.iterations());
}
BENCHMARK(BM_AxisTick);

// Simulated steps per second: both axes jogging with periodic reversals, 10 s of machine time
// per iteration; the counter reports STEP pulses simulated per host second.
void BM_AxisSimulatedSteps(benchmark::State& st) {
  const Config c = bench_config();
  int64_t steps = 0;
  for (auto _ : st) {
    std::array<State, 2> s{};
    for (auto& x : s) {
      x.homed = 1;
      x.pos = 1'000'000;
    }
    for (int t = 0; t < 10'000; ++t) {
      for (size_t a = 0; a < 2; ++a) {
        Input in;
        if (t % 100 == 0) {
          in.cmd = Command{CmdKind::Jog, static_cast<int8_t>((t / 2000 + static_cast<int>(a)) % 2 == 0 ? 1 : -1), 1, 0};
        }
        const StepResult r = step(s[a], in, c);
        s[a] = r.state;
        steps += r.out.steps;
      }
    }
    benchmark::DoNotOptimize(s);
  }
  st.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  st.counters["ticks_per_s"] =
      benchmark::Counter(static_cast<double>(st.iterations()) * 20'000.0, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AxisSimulatedSteps)->Unit(benchmark::kMillisecond);

}  // namespace
