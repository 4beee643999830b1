#include "client/client.hpp"

#include <algorithm>
#include <array>

#include "codec/layout.hpp"
#include "core/frame/command_codec.hpp"
#include "core/frame/echo_builder.hpp"
#include "core/frame/echo_codec.hpp"

namespace ap::client {

std::string to_string(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

std::optional<std::string> format(const frame::CommandFrame& f) {
  std::array<std::uint8_t, codec::kCommandLength> out{};
  if (!frame::format_command(f, out).ok()) return std::nullopt;
  return to_string(out);
}

std::optional<std::string> format(const frame::EchoFrame& f) {
  std::array<std::uint8_t, codec::kEchoLength> out{};
  if (!frame::format_echo(f, out).ok()) return std::nullopt;
  return to_string(out);
}

std::optional<std::string> Client::next_command(frame::CommandFrame f) {
  f.seq = next_seq_;
  auto bytes = format(f);
  if (!bytes) return std::nullopt;
  next_seq_ = static_cast<std::uint16_t>((next_seq_ + 1U) % codec::kSeqModulo);
  in_flight_.push_back(f.seq);
  ++counters_.sent;
  // A silent board still yields lost reports, and an old seq never looks in flight again.
  while (in_flight_.size() > kMaxInFlight) {
    in_flight_.pop_front();
    ++counters_.lost;
  }
  return bytes;
}

std::vector<EchoEvent> Client::receive(const std::string& bytes) {
  return receive(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}

std::vector<EchoEvent> Client::receive(std::span<const std::uint8_t> bytes) {
  std::vector<EchoEvent> events;
  framer_.feed(bytes, [&](const frame::EchoFramer::Event& e) { events.push_back(classify(e)); });
  return events;
}

EchoEvent Client::classify(const frame::EchoFramer::Event& e) {
  EchoEvent ev;
  ev.stream_offset = e.stream_offset;
  if (!e.rejection.ok()) {
    ev.kind = EchoKind::Malformed;
    ev.rejection = e.rejection;
    ++counters_.malformed;
    return ev;
  }
  ev.echo = e.frame;
  if (e.frame.x.status == codec::EchoStatus::FrameRejected || e.frame.y.status == codec::EchoStatus::FrameRejected) {
    const auto& part = e.frame.x.status == codec::EchoStatus::FrameRejected ? e.frame.x : e.frame.y;
    ev.kind = EchoKind::Rejected;
    ev.rejection = frame::rejection_from_code(part.data);
    ++counters_.rejected;
    return ev;
  }
  const auto it = std::find(in_flight_.begin(), in_flight_.end(), e.frame.seq);
  if (it != in_flight_.end()) {
    ev.kind = EchoKind::Matched;
    ev.lost.assign(in_flight_.begin(), it);
    counters_.lost += static_cast<std::uint32_t>(ev.lost.size());
    in_flight_.erase(in_flight_.begin(), it + 1);
    answered_.push_back(e.frame.seq);
    if (answered_.size() > kAnsweredMemory) answered_.pop_front();
    ++counters_.matched;
    return ev;
  }
  if (std::find(answered_.begin(), answered_.end(), e.frame.seq) != answered_.end()) {
    ev.kind = EchoKind::Duplicate;
    ++counters_.duplicated;
    return ev;
  }
  ev.kind = EchoKind::Unexpected;
  ++counters_.unexpected;
  return ev;
}

}  // namespace ap::client
