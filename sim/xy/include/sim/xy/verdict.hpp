// What a run of a scenario is given and what it gives back (docs/sim.md): the options, the
// verdict with its per-board figures, and the verdict as text (report.cpp). A header of its own
// so that the simulated PC, the fault link and the report, which fill and print the verdict,
// do not see the board side's types (sim/xy/board.hpp).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::sim::xy {

struct RunOptions {
  std::string out_root = "out/sim";   // outputs of board 0 under out_root/NAME/ (empty: none)
  bool realtime = false;              // --realtime: virtual time follows the wall clock
  std::int64_t step_us = 10'000;      // lockstep granularity (telemetry sampling)
  std::optional<std::uint32_t> domain;   // default: claim a free one (DomainLease)
  bool join = false;                  // boards already run elsewhere (`axisproof sim board`)
  std::string qemu_image;             // --target qemu: the boards run this image (docs/qemu.md)
  std::ostream* log = nullptr;        // progress and the PC's report
};

struct GapRun {
  std::int64_t t_us;        // when the PC noticed
  std::uint32_t lost;       // retransmission timeouts in a row (no answer in between)
};

struct LinkStats {
  std::uint64_t frames = 0, delivered = 0, dropped = 0, corrupted = 0, duplicated = 0, reordered = 0, delayed = 0,
                cut = 0;
};

// What the client made of the user's commands (docs/protocol.md "Delivery").
struct DeliveryStats {
  std::uint32_t submitted = 0, delivered = 0, failed = 0;
  std::uint64_t new_frames = 0, retransmissions = 0, given_up = 0, frames_answered = 0, frames_taken = 0;
  std::vector<xy_client::Report> reports;   // every settled command, in settling order
  std::uint64_t outcomes_checked = 0;    // reports compared with the board's fate of their frame
};

struct BoardVerdict {
  std::uint32_t board = 0;
  std::uint32_t commands = 0, echoes = 0, lost = 0, rejected = 0, malformed = 0, unexpected = 0, duplicates = 0;
  std::vector<GapRun> gaps;
  LinkStats to_board, to_pc;
  std::uint64_t lost_step_risks = 0;
  std::uint64_t echoes_model_checked = 0, echo_disagreements = 0;   // board side (models/xy/echo)
  std::uint64_t echoes_from_board = 0;                              // echoes the bus brought
  DeliveryStats delivery;
};

struct RunResult {
  bool pass = false;
  std::vector<std::string> failures;   // expectations and safety properties violated
  std::vector<BoardVerdict> boards;
  std::int64_t vtime_us = 0;
  double wall_s = 0.0;
  std::uint64_t bus_round_trips = 0;
  std::uint32_t domain = 0;
  std::string out_dir;
};

// A human-readable verdict (pass/fail, failures, per-board gaps and link statistics).
std::string format_report(const scenario::Scenario& s, const RunResult& r);

}  // namespace ap::sim::xy
