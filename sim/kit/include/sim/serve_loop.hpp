// The board side of one board's bus link, the same for every profile (docs/sim.md): take
// commands in order until a shutdown, an idle timeout or `stop`, and answer each with exactly
// one echo (the lockstep of docs/dds.md).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pc/dds/bus.hpp"

namespace ap::sim {

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
    if ((cmd->flags & dds::kFlagEnv) != 0U) {
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

// The board side of a profile whose unit sends no two-axis telemetry (the bus's type): its Board built
// from `opt` (opt.id is the board's number on the bus) served until a shutdown, `idle_timeout`
// or `stop`; `step(board, cmd)` runs a plain command and returns the bytes the unit sent.
template <class Board, class Options, class Step>
int serve_unit_board(const dds::ParticipantPtr& participant, const Options& opt, std::chrono::milliseconds idle_timeout,
                     const std::atomic<bool>* stop, Step step) {
  dds::BoardEndpoint ep(participant, opt.id);
  Board board(opt);
  const dds::Telemetry none{};  // the bus's two-axis telemetry type: not this unit's (docs/sim.md)
  return serve_loop(
      ep, board, idle_timeout, stop, [&](const dds::CommandSample& cmd) { return step(board, cmd); }, [&] { return none; });
}

// The reply to the environment command `violation INDEX`: the board's safety checker's
// violation number INDEX (0-based, up to 9 digits), or an error line.
inline std::string violation_reply(const std::vector<std::string>& violations, const std::string& index) {
  if (index.empty() || index.size() > 9 || index.find_first_not_of("0123456789") != std::string::npos) {
    return "error violation INDEX";
  }
  const std::size_t i = std::stoul(index);
  if (i >= violations.size()) return "error no violation " + index;
  return violations[i];
}

// Board::finish() of such a profile: trace.csv, waveforms.vcd and plots.svg (titled with the
// run's name, the folder's) under out_dir, none when it is empty. The writers are the
// profile's, found by the rows' type (write_trace_csv, write_vcd, write_svg of its namespace).
template <class Rows>
void write_board_outputs(const std::string& out_dir, const Rows& rows) {
  if (out_dir.empty()) return;
  std::filesystem::create_directories(out_dir);
  write_trace_csv(rows, out_dir + "/trace.csv");
  write_vcd(rows, out_dir + "/waveforms.vcd");
  write_svg(rows, std::filesystem::path(out_dir).filename().string(), out_dir + "/plots.svg");
}

}  // namespace ap::sim
