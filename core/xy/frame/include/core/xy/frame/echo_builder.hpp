#pragma once
// Echo builder: turns the board's current state into an echo frame that always formats.
// Values from the board are clamped into their table ranges (an echo must never fail to
// go out because a sensor read an absurd value); an unknown status becomes FAULT.
#include <cstdint>

#include "core/xy/frame/frames.hpp"

namespace ap::xy_frame {

struct EchoSource {
  void* ctx = nullptr;
  AxisEcho (*axis)(void* ctx, Axis axis) = nullptr;
  std::int32_t (*subscriber)(void* ctx, SubscriberSlot slot) = nullptr;
};

// Echo for an accepted command: `seq` and the slots are copied from it.
EchoFrame build_echo(std::uint16_t seq, const SubscriberSlots& requested, const EchoSource& source);

// Echo for a rejected frame: both axes say FRAME_REJECTED with reason*100 + offset; the
// sequence number is the last accepted one because the rejected frame's own cannot be
// trusted; the subscriber slots are empty.
EchoFrame build_rejection_echo(std::uint16_t last_seq, Rejection rejection);

// reason*100 + offset, the FRAME_REJECTED data; and back.
std::int32_t rejection_code(Rejection rejection);
Rejection rejection_from_code(std::int32_t code);

}  // namespace ap::xy_frame
