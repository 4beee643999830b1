#pragma once
// PC-side link endpoint: numbers command frames, matches echoes to them and tells lost,
// duplicated, rejected and unexpected echoes apart. Echoes arrive in order over the radio
// link, so when seq s is answered every older unanswered seq is declared lost.
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/frame/frames.hpp"
#include "core/frame/stream_framer.hpp"

namespace ap::client {

enum class EchoKind {
  Matched,     // answers a command in flight
  Duplicate,   // answers a command that was already answered
  Rejected,    // the board rejected a frame (reason in `rejection`)
  Unexpected,  // seq never sent or too old to tell
  Malformed,   // the echo itself failed to parse (reason in `rejection`)
};

struct EchoEvent {
  EchoKind kind = EchoKind::Malformed;
  frame::EchoFrame echo{};
  frame::Rejection rejection{};        // Rejected: board's reason; Malformed: parse error
  std::vector<std::uint16_t> lost;     // seqs declared lost by this echo
  std::uint32_t stream_offset = 0;
};

struct ClientCounters {
  std::uint32_t sent = 0;
  std::uint32_t matched = 0;
  std::uint32_t lost = 0;
  std::uint32_t duplicated = 0;
  std::uint32_t rejected = 0;
  std::uint32_t unexpected = 0;
  std::uint32_t malformed = 0;
};

std::string to_string(std::span<const std::uint8_t> bytes);
std::optional<std::string> format(const frame::CommandFrame& f);
std::optional<std::string> format(const frame::EchoFrame& f);

class Client {
 public:
  // Commands not yet answered beyond this many are declared lost, so that seq wrap-around
  // (1000) can never make an old seq look in flight again.
  static constexpr std::size_t kMaxInFlight = 400;
  // How many answered seqs are remembered to recognise duplicates.
  static constexpr std::size_t kAnsweredMemory = 400;

  // Stamps the next seq on the frame and returns its bytes; nullopt (seq unused) if invalid.
  std::optional<std::string> next_command(frame::CommandFrame f);
  std::vector<EchoEvent> receive(std::span<const std::uint8_t> bytes);
  std::vector<EchoEvent> receive(const std::string& bytes);

  const ClientCounters& counters() const { return counters_; }
  const std::deque<std::uint16_t>& in_flight() const { return in_flight_; }
  std::uint16_t next_seq() const { return next_seq_; }

 private:
  EchoEvent classify(const frame::EchoFramer::Event& e);

  std::uint16_t next_seq_ = 0;
  std::deque<std::uint16_t> in_flight_;
  std::deque<std::uint16_t> answered_;
  frame::EchoFramer framer_;
  ClientCounters counters_;
};

}  // namespace ap::client
