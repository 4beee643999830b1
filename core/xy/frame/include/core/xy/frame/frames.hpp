#pragma once
// Decoded frames. Values here are always in their table ranges once parsed; the formatter
// re-checks them because callers may build frames by hand.
#include <array>
#include <cstdint>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/errors.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::xy_frame {

enum class Axis : std::uint8_t { X = 0, Y = 1 };

struct AxisCommand {
  xy_codec::CommandId id = xy_codec::CommandId::Nop;
  std::int32_t data = 0;
  friend constexpr bool operator==(const AxisCommand&, const AxisCommand&) = default;
};

struct SubscriberSlot {
  xy_codec::SubscriberId id = xy_codec::SubscriberId::None;
  std::uint8_t arg = 0;
  friend constexpr bool operator==(const SubscriberSlot&, const SubscriberSlot&) = default;
};

using SubscriberSlots = std::array<SubscriberSlot, xy_codec::kSubscriberSlots>;

struct CommandFrame {
  std::uint16_t seq = 0;  // 0..999
  AxisCommand x;
  AxisCommand y;
  SubscriberSlots subs{};
  friend constexpr bool operator==(const CommandFrame&, const CommandFrame&) = default;
};

struct AxisEcho {
  xy_codec::EchoStatus status = xy_codec::EchoStatus::Idle;
  std::int32_t data = 0;
  friend constexpr bool operator==(const AxisEcho&, const AxisEcho&) = default;
};

struct SubscriberPacket {
  SubscriberSlot slot;
  std::int32_t data = 0;
  friend constexpr bool operator==(const SubscriberPacket&, const SubscriberPacket&) = default;
};

struct EchoFrame {
  std::uint16_t seq = 0;
  AxisEcho x;
  AxisEcho y;
  std::array<SubscriberPacket, xy_codec::kSubscriberSlots> subs{};
  friend constexpr bool operator==(const EchoFrame&, const EchoFrame&) = default;
};

// A typed error and the offset of the first offending byte within the frame.
struct Rejection {
  xy_codec::FrameError error = xy_codec::FrameError::None;
  std::uint16_t offset = 0;
  constexpr bool ok() const { return error == xy_codec::FrameError::None; }
  friend constexpr bool operator==(const Rejection&, const Rejection&) = default;
};

}  // namespace ap::xy_frame
