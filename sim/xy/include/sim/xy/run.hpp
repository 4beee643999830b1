// The simulated PC and the run of a scenario over the DDS test bus (docs/sim.md,
// docs/sim.md).
//
//   serve_board()   the board side: one SimBoard behind one BoardEndpoint; answers every bus
//                   Command (advance virtual time, feed the UART, or an environment command)
//                   with exactly one Echo carrying the UART TX bytes and the telemetry.
//   run_scenario()  the PC side: reads the scenario, sends a command frame every period,
//                   passes frames both ways through the fault injector, decodes echoes,
//                   checks the expectations and the axis safety properties on the telemetry,
//                   and returns a verdict (pass only when nothing was violated). With
//                   RunOptions::join unset it also hosts the boards (one thread each).
// A run's options and its verdict are sim/xy/verdict.hpp's.
#pragma once

#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "pc/dds/bus.hpp"
#include "sim/serve_loop.hpp"
#include "sim/xy/scenario.hpp"
#include "sim/xy/verdict.hpp"
#include "pc/xy/client/client.hpp"

namespace ap::sim::xy {

// The board side's own types (sim/xy/board.hpp), by name only: the users of a run see nothing
// of the board.
struct BoardOptions;
class SimBoard;

// Runs one scenario; throws ap::dds::Error / std::runtime_error on a bus failure.
RunResult run_scenario(const scenario::Scenario& s, const RunOptions& opt);

// Board side of one board on `participant` until a shutdown command (or `idle_timeout`
// without any command). Returns 0 on an orderly shutdown.
int serve_board(const dds::ParticipantPtr& participant, const BoardOptions& opt, std::chrono::milliseconds idle_timeout,
                const std::atomic<bool>* stop = nullptr);

// The telemetry sample of a board.
dds::Telemetry telemetry_of(SimBoard& b, std::uint32_t id);

}  // namespace ap::sim::xy
