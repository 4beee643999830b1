#pragma once
// Board-side receive path: UART bytes -> framer -> dispatch -> one echo per frame event.
//
// What a rejected frame may change (issue 3 item 6): the counters and the echo it causes.
// It does not run a handler, does not refresh the link watchdog (ticks_since_accepted keeps
// growing) and does not move last_seq. The framer is the link layer only (syntax and CRC);
// an intact frame whose command ID is outside the table, whose data is out of range or
// whose command has no handler is rejected the same way by the callback table
// (unknown_command, data_out_of_range, unhandled), and counted in unhandled_frames.
#include <cstdint>
#include <span>

#include "codec/layout.hpp"
#include "core/frame/callback_table.hpp"
#include "core/frame/echo_builder.hpp"
#include "core/frame/echo_codec.hpp"
#include "core/frame/stream_framer.hpp"

namespace ap::frame {

struct LinkCounters {
  FramerCounters framer;
  std::uint32_t unhandled_frames = 0;
  std::uint32_t refused_parts = 0;  // axis parts whose handler answered Refused
  friend constexpr bool operator==(const LinkCounters&, const LinkCounters&) = default;
};

class CommandLink {
 public:
  CommandLink(const CallbackTable& table, void* handler_ctx, EchoSource source)
      : table_(table), handler_ctx_(handler_ctx), source_(source) {}

  // sink(std::span<const std::uint8_t, codec::kEchoLength>) receives each echo to send.
  template <class Sink>
  void receive(std::span<const std::uint8_t> bytes, Sink&& sink) {
    framer_.feed(bytes, [&](const RawCommandFramer::Event& event) {
      const EchoFrame echo = handle(event);
      std::array<std::uint8_t, codec::kEchoLength> out{};
      // build_* only produce in-range echoes, so formatting cannot fail.
      if (format_echo(echo, out).ok()) sink(std::span<const std::uint8_t, codec::kEchoLength>(out));
    });
  }

  // One watchdog tick of the caller's clock; saturates instead of wrapping.
  void tick() {
    if (ticks_since_accepted_ != UINT32_MAX) ++ticks_since_accepted_;
  }
  std::uint32_t ticks_since_accepted() const { return ticks_since_accepted_; }
  std::uint16_t last_seq() const { return last_seq_; }
  LinkCounters counters() const { return {framer_.counters(), unhandled_frames_, refused_parts_}; }
  Rejection last_rejection() const { return last_rejection_; }

  // Exposed for callers that frame bytes themselves (e.g. a fixed-length DMA receive).
  EchoFrame handle(const RawCommandFramer::Event& event);

 private:
  const CallbackTable& table_;
  void* handler_ctx_;
  EchoSource source_;
  RawCommandFramer framer_{};
  std::uint32_t ticks_since_accepted_ = 0;
  std::uint16_t last_seq_ = 0;
  std::uint32_t unhandled_frames_ = 0;
  std::uint32_t refused_parts_ = 0;
  Rejection last_rejection_{};
};

}  // namespace ap::frame
