// The simulated PC and board in lockstep (docs/sim.md): bus frames per wall
// second and virtual time per wall time, running a bundled scenario end to end over DDS (board
// in-process, outputs off), and the simulated board alone (ticks per second, no bus).
// The DDS round trip beside ddsperf is bench/dds.cpp.
#include <benchmark/benchmark.h>

#include <string>

#include "sim/xy/scenario.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "sim/xy/board.hpp"
#include "sim/xy/run.hpp"

namespace {

void BM_SimScenarioLockstep(benchmark::State& state) {
  const ap::sim::xy::scenario::Scenario s =
      ap::sim::xy::scenario::parse_file(std::string(AP_SOURCE_DIR) + "/scenarios/xy/absolute_20mm.scn");
  ap::sim::xy::RunOptions o;
  o.out_root = "";
  double vtime = 0, wall = 0, trips = 0;
  for (auto _ : state) {
    const ap::sim::xy::RunResult r = ap::sim::xy::run_scenario(s, o);
    if (!r.pass) state.SkipWithError("scenario failed");
    vtime += static_cast<double>(r.vtime_us) / 1e6;
    wall += r.wall_s;
    trips += static_cast<double>(r.bus_round_trips);
  }
  state.counters["frames_per_s"] = trips / wall;
  state.counters["sim_over_wall"] = vtime / wall;
}
BENCHMARK(BM_SimScenarioLockstep)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

void BM_SimBoardAlone(benchmark::State& state) {
  ap::sim::xy::SimBoard b(ap::sim::xy::BoardOptions{});
  b.boot();
  ap::xy_frame::CommandFrame f;
  f.x = {ap::xy_codec::CommandId::Jog, 1};
  std::int64_t t = 0;
  std::uint16_t seq = 0;
  for (auto _ : state) {
    f.seq = static_cast<std::uint16_t>(++seq % ap::xy_codec::kSeqModulo);
    std::array<std::uint8_t, ap::xy_codec::kCommandLength> bytes{};
    (void)ap::xy_frame::format_command(f, bytes);
    b.rx(bytes);
    t += 100'000;
    b.advance_to(t);
    benchmark::DoNotOptimize(b.take_tx(1024));
  }
  state.counters["ticks_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 100, benchmark::Counter::kIsRate);
  state.counters["sim_over_wall"] = benchmark::Counter(static_cast<double>(state.iterations()) * 0.1, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimBoardAlone)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
