#pragma once
// PC-side link endpoint: delivers the user's commands to the board exactly once and in the
// order issued over a link that drops, corrupts, duplicates, reorders and delays frames, or
// reports each one it could not deliver with a typed outcome (docs/protocol.md "Delivery").
//
// One frame is in flight at a time. It is sent again, byte for byte, until an echo with its
// seq answers it; only then does the next frame take the next seq. The board runs a frame only
// when its seq is newer than the last one it took, so a repeat or a late copy never runs twice,
// and the echo of a repeat tells the same outcome as the first one. A stop jumps the queue.
//
// Time is given by the caller (microseconds, any origin, never decreasing), so the same
// inputs give the same frames: the simulated PC runs it in virtual time.
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/xy/codec/layout.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "core/xy/frame/frames.hpp"
#include "core/xy/frame/stream_framer.hpp"

namespace ap::xy_client {

std::string to_string(std::span<const std::uint8_t> bytes);
std::optional<std::string> format(const xy_frame::CommandFrame& f);
std::optional<std::string> format(const xy_frame::EchoFrame& f);

// Which part of a frame a command goes in: an axis command in its axis's part, a unit-scope
// command (parameters, save, sleep, clear) in whichever part is free.
enum class Part : std::uint8_t { X, Y, Unit };

struct Command {
  Part part = Part::Unit;
  xy_frame::AxisCommand cmd{};
};

// How a command ended (docs/protocol.md "Delivery", "Outcomes").
enum class Outcome : std::uint8_t {
  Done,         // the board took its frame and ran it
  Refused,      // the board took its frame and refused it (COMMAND_REFUSED: not possible now)
  Blocked,      // the board took its frame while blocked (BLOCKED_*): not run
  Superseded,   // a later stop of the same axis cancelled it before it was sent
  Unconfirmed,  // no answer within the retry budget: it took effect at most once
  LinkDown,     // issued while the link was down (or queued when it went down): never sent
  Invalid,      // not a valid command (an ID or data outside the tables): never sent
};
const char* to_string(Outcome o);
constexpr bool delivered(Outcome o) { return o == Outcome::Done || o == Outcome::Refused || o == Outcome::Blocked; }

using Ticket = std::uint64_t;

struct Report {
  Ticket ticket = 0;
  Command command{};
  Outcome outcome = Outcome::Done;
  std::optional<std::uint16_t> seq;  // the frame that carried it (none if never sent)
  std::optional<std::uint8_t> part;  // the part of that frame it rode in: 0 X, 1 Y
  std::int64_t issued_us = 0;
  std::optional<std::int64_t> first_sent_us;
  std::int64_t settled_us = 0;        // when the outcome was known
  std::uint32_t transmissions = 0;    // of its frame
  xy_codec::EchoStatus status = xy_codec::EchoStatus::Idle;  // its part's status in the answering echo
  std::int32_t data = 0;
};

struct Config {
  std::int64_t retransmit_us = 40'000;   // no answer this long: send the frame again
  std::uint32_t max_transmissions = 100; // then the frame is given up (4 s at 40 ms)
  std::int64_t keepalive_us = 100'000;   // thesis §6.2: a frame every 100 ms when idle
  std::uint16_t first_seq = 0;
  // Factory parameters (docs/storage.md "Factory and user parameters": pitch, steps, usteps,
  // irun, ihold) are sent only by a client opened for factory work; otherwise such a command
  // settles `invalid` at once and never reaches the board.
  bool factory = false;
};

// What rides along in every new frame: the held jog level of each axis (sent in a free part,
// so a held key keeps the board's link watchdog fed) and the subscriber slots.
struct Extras {
  std::array<std::int32_t, 2> jog{};  // 0 = no jog held
  xy_frame::SubscriberSlots subs{};
};

enum class EchoKind {
  Answer,     // answers the frame in flight: its commands are settled
  Late,       // a repeat's second answer, or an echo for a frame already settled
  Resync,     // the board took a newer frame than the client sent: the frame in flight is renumbered
  Rejected,   // the board rejected a frame (reason in `rejection`); the frame is sent again
  Malformed,  // the echo itself failed to parse (reason in `rejection`)
};

struct EchoEvent {
  EchoKind kind = EchoKind::Malformed;
  xy_frame::EchoFrame echo{};
  xy_frame::CommandFrame answered{};  // Answer: the frame it answers
  xy_frame::Rejection rejection{};
  std::uint32_t stream_offset = 0;
};

struct ClientCounters {
  std::uint32_t sent = 0;             // frames on the wire, repeats included
  std::uint32_t new_frames = 0;       // frames that took a seq
  std::uint32_t retransmissions = 0;  // sent again after a timeout or a rejection echo
  std::uint32_t timeouts = 0;         // retransmit_us passed with no answer
  std::uint32_t answered = 0;
  std::uint32_t late = 0;
  std::uint32_t rejected = 0;
  std::uint32_t malformed = 0;
  std::uint32_t resyncs = 0;
  std::uint32_t given_up = 0;         // frames that ran out of transmissions
  std::uint32_t commands = 0;         // submitted
  std::uint32_t delivered = 0;        // Done + Refused + Blocked
  std::uint32_t failed = 0;           // Superseded + Unconfirmed + LinkDown + Invalid
};

class Client {
 public:
  explicit Client(Config c = {});

  // Queues a user command (a stop goes ahead of everything queued and cancels the queued
  // motion commands of its axis). While the link is down the command fails at once.
  Ticket submit(const Command& c, std::int64_t now_us);

  // The bytes to send now: a new frame, a repeat of the one in flight, a keep-alive, or none.
  std::optional<std::string> poll(std::int64_t now_us, const Extras& extras);

  std::vector<EchoEvent> receive(std::span<const std::uint8_t> bytes, std::int64_t now_us);
  std::vector<EchoEvent> receive(const std::string& bytes, std::int64_t now_us);

  // Settled commands since the last call, in the order they settled.
  std::vector<Report> take_reports();

  const ClientCounters& counters() const { return counters_; }
  bool link_down() const { return link_down_; }
  bool idle() const { return !in_flight_ && queue_.empty(); }
  std::size_t queued() const { return queue_.size(); }
  std::optional<std::uint16_t> in_flight_seq() const;
  std::uint16_t next_seq() const { return next_seq_; }
  const Config& config() const { return cfg_; }

 private:
  struct Pending {
    Ticket ticket = 0;
    Command command{};
    std::int64_t issued_us = 0;
    // Stops of the same axis issued while this stop was still queued: they ride with it and
    // settle with its outcome (one stop frame, not one per key press).
    std::vector<std::pair<Ticket, std::int64_t>> riders;
  };
  struct InFlight {
    xy_frame::CommandFrame frame{};
    std::string bytes;
    std::vector<Pending> commands;  // 0..2, X part first
    std::array<int, 2> part_of{};   // which part (0 = X, 1 = Y) each command occupies
    std::int64_t first_sent_us = 0;
    std::int64_t last_sent_us = 0;
    std::uint32_t transmissions = 0;
    bool resend_now = false;
  };

  void start_frame(std::int64_t now_us, const Extras& extras);
  std::string send(std::int64_t now_us);
  void settle(const xy_frame::EchoFrame& echo, std::int64_t now_us);
  // Settles one command (and the stops riding with it): `f` its frame if it went out, `part`
  // its part of the answering echo.
  void report(const Pending& p, Outcome o, std::int64_t now_us, const InFlight* f, const xy_frame::AxisEcho* part);
  std::int64_t retransmit_interval() const;
  EchoEvent classify(const xy_frame::EchoFramer::Event& e, std::int64_t now_us);

  Config cfg_;
  std::uint16_t next_seq_ = 0;
  Ticket next_ticket_ = 1;
  std::deque<Pending> queue_;
  std::optional<InFlight> in_flight_;
  std::optional<std::int64_t> last_new_frame_us_;
  bool link_down_ = false;
  std::vector<Report> reports_;
  xy_frame::EchoFramer framer_;
  ClientCounters counters_;
};

}  // namespace ap::xy_client
