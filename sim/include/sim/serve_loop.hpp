// The board side of one board's bus link, the same for every profile (docs/sim.md): take
// commands in order until a shutdown, an idle timeout or `stop`, and answer each with exactly
// one echo (the lockstep of docs/dds.md).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "pc/dds/bus.hpp"

namespace ap::sim {

// Bus Command flag of a harness ("environment") command: bytes are a text line for the
// board's env(), the echo's bytes its text reply; the board's clock does not move.
inline constexpr std::uint32_t kFlagEnv = 0x100;

// `board` provides finish() (write its outputs), env(text) -> reply text, and the profile's
// `step(cmd)` runs a plain command (advance to its time, feed its bytes) and returns the bytes
// the board's UART sent; `telemetry()` is the sample each echo carries. Returns 0 after a
// shutdown command, 1 when `stop` was set, 2 after `idle_timeout` without a command.
template <class Board, class Step, class TelemetryOf>
int serve_loop(dds::BoardEndpoint& ep, Board& board, std::chrono::milliseconds idle_timeout,
               const std::atomic<bool>* stop, Step step, TelemetryOf telemetry) {
  for (;;) {
    if (stop != nullptr && stop->load()) return 1;
    auto cmd = ep.take_command(std::chrono::milliseconds(stop != nullptr ? 200 : idle_timeout.count()));
    if (!cmd) {
      if (stop != nullptr) {
        idle_timeout -= std::chrono::milliseconds(200);
        if (idle_timeout.count() > 0) continue;
      }
      return 2;
    }
    if ((cmd->flags & dds::kFlagShutdown) != 0U) {
      board.finish();
      ep.echo(*cmd, {}, telemetry());
      return 0;
    }
    if ((cmd->flags & kFlagEnv) != 0U) {
      std::string reply = board.env(std::string(cmd->bytes.begin(), cmd->bytes.end()));
      if (reply.size() > dds::kFrameMax) reply.resize(dds::kFrameMax);
      const std::vector<std::uint8_t> bytes(reply.begin(), reply.end());
      ep.echo(*cmd, bytes, telemetry());
      continue;
    }
    const std::vector<std::uint8_t> tx = step(*cmd);
    ep.echo(*cmd, tx, telemetry());
  }
}

}  // namespace ap::sim
