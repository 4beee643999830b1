#pragma once
// Stream framer: UART bytes in arbitrary chunks -> whole frames or typed rejections.
//
// Resync rule: the start character never occurs inside a frame, so
//   - while hunting, every byte that is not a start character is discarded (counted);
//   - a start character inside a partial frame abandons it (BadLength) and starts anew;
//   - an end character before the fixed length abandons the partial frame (BadLength).
// Hence garbage before or between frames can never swallow a following valid frame, and a
// lost byte costs exactly the frame it was in. The framer works byte by byte with a fixed
// buffer, so how the stream is chunked cannot change what comes out.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/frame/frames.hpp"

namespace ap::xy_frame {

struct CommandCodec {
  using Frame = CommandFrame;
  static constexpr std::uint8_t kStart = static_cast<std::uint8_t>(xy_codec::kCommandStart);
  static constexpr std::size_t kLength = xy_codec::kCommandLength;
  static Rejection parse(std::span<const std::uint8_t> b, Frame& f) { return parse_command(b, f); }
};

// The board's receive path: the link layer only (decode_command: syntax and CRC). An intact
// frame with an ID outside the command table comes out accepted and is rejected by the
// callback table's own bound check (CallbackTable::lookup), as in Klipper's command_dispatch.
struct RawCommandCodec {
  using Frame = CommandFrame;
  static constexpr std::uint8_t kStart = static_cast<std::uint8_t>(xy_codec::kCommandStart);
  static constexpr std::size_t kLength = xy_codec::kCommandLength;
  static Rejection parse(std::span<const std::uint8_t> b, Frame& f) { return decode_command(b, f); }
};

struct EchoCodec {
  using Frame = EchoFrame;
  static constexpr std::uint8_t kStart = static_cast<std::uint8_t>(xy_codec::kEchoStart);
  static constexpr std::size_t kLength = xy_codec::kEchoLength;
  static Rejection parse(std::span<const std::uint8_t> b, Frame& f) { return parse_echo(b, f); }
};

// Counters wrap at 2^32; at 10 frames/s that is 13 years.
struct FramerCounters {
  std::uint32_t accepted_frames = 0;
  std::uint32_t rejected_frames = 0;
  std::uint32_t rejected_bytes = 0;  // garbage while hunting plus bytes of rejected frames
  friend constexpr bool operator==(const FramerCounters&, const FramerCounters&) = default;
};

template <class Frame>
struct FramerEvent {
  Frame frame{};            // meaningful only when rejection.ok()
  Rejection rejection{};    // offset is relative to the frame's first byte
  std::uint32_t stream_offset = 0;  // of the frame's first byte (wraps at 2^32)
  std::uint16_t length = 0;         // bytes the frame occupied in the stream
  friend constexpr bool operator==(const FramerEvent&, const FramerEvent&) = default;
};

template <class Codec>
class StreamFramer {
 public:
  using Frame = typename Codec::Frame;
  using Event = FramerEvent<Frame>;

  std::optional<Event> push(std::uint8_t byte) {
    const std::uint32_t here = position_++;
    if (length_ == 0) {
      if (byte == Codec::kStart) {
        begin(byte, here);
      } else {
        ++counters_.rejected_bytes;
      }
      return std::nullopt;
    }
    if (byte == Codec::kStart) {
      Event e = abandon(length_);
      begin(byte, here);
      return e;
    }
    buffer_[length_++] = byte;
    if (length_ == Codec::kLength) return complete();
    if (byte == static_cast<std::uint8_t>(xy_codec::kEnd)) return abandon(length_ - 1U);
    return std::nullopt;
  }

  // Calls sink(const Event&) for every frame or rejection completed by these bytes.
  template <class Sink>
  void feed(std::span<const std::uint8_t> bytes, Sink&& sink) {
    for (const std::uint8_t b : bytes) {
      if (auto e = push(b)) sink(*e);
    }
  }

  const FramerCounters& counters() const { return counters_; }
  std::size_t pending() const { return length_; }

 private:
  void begin(std::uint8_t byte, std::uint32_t at) {
    buffer_[0] = byte;
    length_ = 1;
    start_ = at;
  }

  Event abandon(std::size_t offset) {
    Event e;
    e.rejection = {xy_codec::FrameError::BadLength, static_cast<std::uint16_t>(offset)};
    e.stream_offset = start_;
    e.length = static_cast<std::uint16_t>(length_);
    ++counters_.rejected_frames;
    counters_.rejected_bytes += static_cast<std::uint32_t>(length_);
    length_ = 0;
    return e;
  }

  Event complete() {
    Event e;
    e.rejection = Codec::parse(std::span<const std::uint8_t>(buffer_, length_), e.frame);
    e.stream_offset = start_;
    e.length = static_cast<std::uint16_t>(length_);
    if (e.rejection.ok()) {
      ++counters_.accepted_frames;
    } else {
      ++counters_.rejected_frames;
      counters_.rejected_bytes += static_cast<std::uint32_t>(length_);
    }
    length_ = 0;
    return e;
  }

  // A plain array on purpose: clang's -fsanitize=bounds (asan and fuzz presets) checks every
  // index into it, so a write one past the end is a finding even though the bytes after it
  // belong to this object (ASan alone cannot see that; nor is std::array::operator[]
  // checked under libstdc++ without assertions).
  std::uint8_t buffer_[Codec::kLength]{};  // NOLINT(*-avoid-c-arrays)
  std::size_t length_ = 0;
  std::uint32_t start_ = 0;
  std::uint32_t position_ = 0;
  FramerCounters counters_{};
};

using CommandFramer = StreamFramer<CommandCodec>;
using RawCommandFramer = StreamFramer<RawCommandCodec>;
using EchoFramer = StreamFramer<EchoCodec>;

}  // namespace ap::xy_frame
