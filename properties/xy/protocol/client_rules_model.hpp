#pragma once
// Test-side reference model of the delivery client's queue and seq rules, written from
// docs/protocol.md alone -- section "Delivery: every command exactly once, in order" (the six
// numbered client rules under "Client (PC side)", the board's seq table under "Board", the
// "Outcomes" table) and section "ID tables" / "Commands" (the table and the note under it on
// goto_slow and move_slow) -- never from pc/xy/client/src/client.cpp. It is an oracle for
// protocol_client_rules_test.cpp: given the same submits and board answers as a real
// ap::xy_client::Client, it predicts
//   - which queued commands a stop cancels (`superseded`, rule 5),
//   - the contents of every new frame, so the order in which commands leave and which of them
//     share a frame (rules 4 and 5),
//   - the seq of every new frame, across the 999 -> 000 wrap and after the board was found
//     ahead of the client (rules 1 and 6).
// It deliberately models only what those rules state; timing (40 ms repeats, 100 ms
// keep-alives) and the retry budget are left to the harness, which polls every keep-alive
// period and answers well inside the budget.
//
// One reading the document leaves open, and what the model does about it:
//   - Rule 4: "A unit-scope command takes the part whose axis holds no jog." With no jog held
//     both parts qualify; the model puts it in the X part, the only part behind which rule 4
//     lets the next command ride ("behind an X command a Y or unit-scope command"). The harness
//     holds no jog, so the other readings of that sentence (a jog held on one axis) are not
//     exercised here.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "protocol/xy/codec/commands.hpp"

namespace ap::test::client_rules {

using xy_codec::CommandId;

// Which part of a frame a command is issued for (docs/protocol.md "Commands", column "scope":
// an axis command acts on the axis of its part; a unit command on the whole board).
enum class Part : std::uint8_t { X, Y, Unit };

enum class Scope : std::uint8_t { Axis, Unit };

// The "Commands" table of docs/protocol.md, transcribed: the scope column, and whether a later
// stop of the same axis cancels the command while it is still queued. Rule 5 ("Stop first")
// names the motion commands goto, move, home and jog; the paragraph under the table adds that
// goto_slow and move_slow are "superseded and stopped the same way" as goto and move. Nothing
// else of its axis is cancelled: not the parameter sets (they do not move the axis), not nop,
// not a stop (a second stop rides with the first, rule 5). The coordinated path commands line,
// centre, arc_cw, arc_ccw (either part) and path_end are cancelled by a stop of either axis
// (rule 5: "on a stop of *either* axis"; docs/cnc.md "Stops"). A switch with no default, so a
// new table row does not compile here (-Werror=switch) until it is classified.
struct Row {
  Scope scope;
  bool cancelled_by_stop;     // by a stop of its own axis
  bool path = false;          // by a stop of either axis
};

constexpr Row row(CommandId id) {
  switch (id) {
    case CommandId::Nop: return {Scope::Axis, false};            // 00 nop
    case CommandId::Stop: return {Scope::Axis, false};           // 01 stop (rides, rule 5)
    case CommandId::Jog: return {Scope::Axis, true};             // 02 jog (rule 5)
    case CommandId::Goto: return {Scope::Axis, true};            // 03 goto (rule 5)
    case CommandId::Move: return {Scope::Axis, true};            // 04 move (rule 5)
    case CommandId::Home: return {Scope::Axis, true};            // 05 home (rule 5)
    case CommandId::SetFastSpeed: return {Scope::Axis, false};   // 06 fast
    case CommandId::SetSlowSpeed: return {Scope::Axis, false};   // 07 slow
    case CommandId::SetAccel: return {Scope::Axis, false};       // 08 accel
    case CommandId::SetStartSpeed: return {Scope::Axis, false};  // 09 start
    case CommandId::SetPitch: return {Scope::Axis, false};       // 10 pitch
    case CommandId::SetSteps: return {Scope::Axis, false};       // 11 steps
    case CommandId::SetMicrosteps: return {Scope::Axis, false};  // 12 usteps
    case CommandId::SetIrun: return {Scope::Axis, false};        // 13 irun
    case CommandId::SetIhold: return {Scope::Axis, false};       // 14 ihold
    case CommandId::PeriphOff: return {Scope::Unit, false};      // 15 sleep
    case CommandId::PeriphOn: return {Scope::Unit, false};       // 16 wake
    case CommandId::SaveParams: return {Scope::Unit, false};     // 17 save
    case CommandId::ClearFault: return {Scope::Unit, false};     // 18 clear
    case CommandId::PathLine: return {Scope::Axis, false, true};       // 19 line
    case CommandId::PathCentre: return {Scope::Axis, false, true};     // 20 centre
    case CommandId::PathArcCw: return {Scope::Axis, false, true};      // 21 arc_cw
    case CommandId::PathArcCcw: return {Scope::Axis, false, true};     // 22 arc_ccw
    case CommandId::PathEnd: return {Scope::Unit, false, true};        // 23 path_end
    case CommandId::GotoSlow: return {Scope::Axis, true};        // 24 goto_slow (note under the table)
    case CommandId::MoveSlow: return {Scope::Axis, true};        // 25 move_slow (note under the table)
  }
  return {Scope::Axis, false};
}

inline constexpr std::size_t kTableRows = 26;  // IDs 00..25 in the "Commands" table
static_assert(kTableRows == xy_codec::kCommandCount, "a row was added to the Commands table: classify it in row()");

// seq 000..999, +1 per new frame, wrapping (docs/protocol.md "Command frame", field seq).
inline constexpr std::uint16_t kSeqSpace = 1000;
constexpr std::uint16_t after(std::uint16_t s) { return static_cast<std::uint16_t>((s + 1U) % kSeqSpace); }

struct Cmd {
  Part part = Part::Unit;
  CommandId id = CommandId::Nop;
  std::int32_t data = 0;
};

constexpr bool is_stop(const Cmd& c) { return c.part != Part::Unit && c.id == CommandId::Stop; }

using Ticket = std::uint64_t;

// What one part of a frame carries; `ticket` empty for a free part (nop 000000: no jog held).
struct PartContent {
  CommandId id = CommandId::Nop;
  std::int32_t data = 0;
  std::optional<Ticket> ticket;
};

struct Frame {
  std::uint16_t seq = 0;
  std::array<PartContent, 2> part{};      // [0] the X part, [1] the Y part (wire order)
  std::vector<Ticket> tickets;            // every command it settles: carried ones and riding stops
};

class Model {
 public:
  explicit Model(std::uint16_t first_seq) : next_seq_(static_cast<std::uint16_t>(first_seq % kSeqSpace)) {}

  // A valid command submitted while the link is up. Returns the tickets it supersedes.
  std::vector<Ticket> submit(Ticket t, const Cmd& c) {
    std::vector<Ticket> gone;
    if (!is_stop(c)) {
      queue_.push_back({t, c, {}});
      return gone;
    }
    // Rule 5: "Motion commands of its axis (goto, move, home, jog) issued before it and still
    // queued end superseded" -- queued only: the frame in flight "may already have run".
    for (auto it = queue_.begin(); it != queue_.end();) {
      if ((it->cmd.part == c.part && row(it->cmd.id).cancelled_by_stop) || row(it->cmd.id).path) {
        gone.push_back(it->ticket);
        it = queue_.erase(it);
      } else {
        ++it;
      }
    }
    // Rule 5: "A second stop of the axis while the first is queued rides with it and gets its
    // outcome." Otherwise the stop "goes ahead of every queued command (behind other queued
    // stops)".
    auto pos = queue_.begin();
    for (; pos != queue_.end() && is_stop(pos->cmd); ++pos) {
      if (pos->cmd.part == c.part) {
        pos->riders.push_back(t);
        return gone;
      }
    }
    queue_.insert(pos, Entry{t, c, {}});
    return gone;
  }

  bool in_flight() const { return flight_.has_value(); }
  const Frame& frame_in_flight() const { return *flight_; }
  std::size_t queued() const { return queue_.size(); }
  std::uint16_t next_seq() const { return next_seq_; }

  // Nothing in flight: the next frame leaves (commands queued, or a keep-alive, rule 3). Rule 1:
  // it takes the next seq. Rule 4 packs it.
  const Frame& start_frame() {
    Frame f;
    f.seq = next_seq_;
    next_seq_ = after(next_seq_);
    if (!queue_.empty()) {
      const Entry first = pop();
      // Rule 4: an axis command in its axis's part; a unit command in the part whose axis holds
      // no jog -- no jog is held here, and the model takes X (see the note at the top).
      const int p = first.cmd.part == Part::Y ? 1 : 0;
      place(f, p, first);
      if (!queue_.empty()) {
        const Cmd& next = queue_.front().cmd;
        // Rule 4: "behind an X command a Y or unit-scope command" (the board runs the X part
        // first, so issue order is kept) ...
        if (p == 0 && next.part != Part::X) {
          place(f, 1, pop());
        } else if (p == 1 && is_stop(first.cmd) && is_stop(next) && next.part == Part::X) {
          // ... "behind a stop of Y a stop of X (stops of different axes commute)".
          place(f, 0, pop());
        }
      }
    }
    flight_ = std::move(f);
    return *flight_;
  }

  // An echo with the frame's own seq answered it (rule 1): the next frame may leave.
  Frame answered() {
    Frame f = std::move(*flight_);
    flight_.reset();
    return f;
  }

  // Rule 6: an echo whose seq is 1..500 ahead of the frame in flight: "the frame in flight is
  // renumbered to follow the board's seq"; rule 1: the next new frame takes the next seq after
  // it (a seq is never reused: the board would answer a reused seq as a repeat and run nothing,
  // "Board" table). Returns false (and changes nothing) outside 1..500.
  bool board_at(std::uint16_t board_seq) {
    if (!flight_) return false;
    const unsigned ahead = (unsigned{board_seq} + kSeqSpace - flight_->seq) % kSeqSpace;
    if (ahead < 1 || ahead > kSeqSpace / 2) return false;
    flight_->seq = after(board_seq);
    next_seq_ = after(flight_->seq);
    return true;
  }

 private:
  struct Entry {
    Ticket ticket = 0;
    Cmd cmd;
    std::vector<Ticket> riders;
  };

  Entry pop() {
    Entry e = queue_.front();
    queue_.pop_front();
    return e;
  }

  static void place(Frame& f, int p, const Entry& e) {
    f.part[static_cast<std::size_t>(p)] = {e.cmd.id, e.cmd.data, e.ticket};
    f.tickets.push_back(e.ticket);
    f.tickets.insert(f.tickets.end(), e.riders.begin(), e.riders.end());
  }

  std::uint16_t next_seq_;
  std::deque<Entry> queue_;
  std::optional<Frame> flight_;
};

}  // namespace ap::test::client_rules
