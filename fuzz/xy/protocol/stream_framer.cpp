// Stream framer fuzz target. The first byte picks a chunk size; oracles: chunked feeding
// gives the same events and counters as byte-at-a-time feeding; every byte is accepted,
// rejected or pending; every accepted frame is the exact bytes at its stream offset.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/frame/stream_framer.hpp"
#include "crc_repair.hpp"

namespace {

constexpr std::size_t kMaxInput = 600;

constexpr std::size_t kMaxEvents = 4096;

template <class Framer, std::size_t N, class Format>
void check(std::span<const std::uint8_t> in, std::size_t chunk, Format format) {
  using Event = typename Framer::Event;
  static std::array<Event, kMaxEvents> whole;
  std::size_t n_whole = 0;
  Framer a;
  for (const std::uint8_t b : in) {
    if (auto e = a.push(b); e && n_whole < kMaxEvents) whole[n_whole++] = *e;
  }
  Framer b;
  std::size_t n = 0;
  bool same = true;
  for (std::size_t at = 0; at < in.size(); at += chunk) {
    const std::size_t len = at + chunk <= in.size() ? chunk : in.size() - at;
    b.feed(in.subspan(at, len), [&](const Event& e) {
      same = same && n < n_whole && e == whole[n];
      ++n;
    });
  }
  ap::fuzz::require(same && (n == n_whole || n_whole == kMaxEvents));
  ap::fuzz::require(a.counters() == b.counters() && a.pending() == b.pending());
  const auto& c = a.counters();
  ap::fuzz::require(c.rejected_bytes + c.accepted_frames * N + a.pending() == in.size());
  for (std::size_t i = 0; i < n_whole; ++i) {
    if (!whole[i].rejection.ok()) continue;
    std::array<std::uint8_t, N> bytes{};
    ap::fuzz::require(format(whole[i].frame, bytes).ok());
    ap::fuzz::require(whole[i].stream_offset + N <= in.size());
    ap::fuzz::require(std::memcmp(in.data() + whole[i].stream_offset, bytes.data(), N) == 0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A dozen frames is plenty to reach every framer state; longer inputs only slow the run.
  if (size == 0 || size > kMaxInput) return 0;
  const std::size_t chunk = 1U + data[0] % 97U;
  const std::span<const std::uint8_t> in(data + 1, size - 1);
  check<ap::xy_frame::CommandFramer, ap::xy_codec::kCommandLength>(in, chunk, ap::xy_frame::format_command);
  check<ap::xy_frame::EchoFramer, ap::xy_codec::kEchoLength>(in, chunk, ap::xy_frame::format_echo);
  return 0;
}
