#pragma once
// RapidCheck generators for valid frames, drawn from the codec tables so that a new table
// entry is covered without touching the tests.
#include <rapidcheck.h>

#include <string>

#include "protocol/codec/commands.hpp"
#include "protocol/codec/statuses.hpp"
#include "protocol/codec/subscribers.hpp"
#include "core/frame/frames.hpp"

namespace ap::test {

inline rc::Gen<frame::AxisCommand> genAxisCommand() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, codec::kCommandCount), [](std::size_t i) {
    const auto& info = codec::kCommands[i];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1),
                        [id = info.id](std::int32_t d) { return frame::AxisCommand{id, d}; });
  });
}

inline rc::Gen<frame::SubscriberSlot> genSlot() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, codec::kSubscriberCount), [](std::size_t i) {
    const auto& info = codec::kSubscribers[i];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.arg_range.min, info.arg_range.max + 1),
                        [id = info.id](std::int32_t a) { return frame::SubscriberSlot{id, static_cast<std::uint8_t>(a)}; });
  });
}

inline rc::Gen<frame::CommandFrame> genCommand() {
  return rc::gen::apply(
      [](std::uint16_t seq, frame::AxisCommand x, frame::AxisCommand y, frame::SubscriberSlot a, frame::SubscriberSlot b,
         frame::SubscriberSlot c, frame::SubscriberSlot d) {
        return frame::CommandFrame{seq, x, y, {a, b, c, d}};
      },
      rc::gen::inRange<std::uint16_t>(0, codec::kSeqModulo), genAxisCommand(), genAxisCommand(), genSlot(), genSlot(),
      genSlot(), genSlot());
}

inline rc::Gen<frame::AxisEcho> genAxisEcho() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, codec::kStatusCount), [](std::size_t i) {
    const auto& info = codec::kStatuses[i];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1),
                        [id = info.id](std::int32_t d) { return frame::AxisEcho{id, d}; });
  });
}

inline rc::Gen<frame::SubscriberPacket> genPacket() {
  return rc::gen::mapcat(genSlot(), [](frame::SubscriberSlot s) {
    const auto& info = codec::kSubscribers[static_cast<std::size_t>(s.id)];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1),
                        [s](std::int32_t d) { return frame::SubscriberPacket{s, d}; });
  });
}

inline rc::Gen<frame::EchoFrame> genEcho() {
  return rc::gen::apply(
      [](std::uint16_t seq, frame::AxisEcho x, frame::AxisEcho y, frame::SubscriberPacket a, frame::SubscriberPacket b,
         frame::SubscriberPacket c, frame::SubscriberPacket d) {
        return frame::EchoFrame{seq, x, y, {a, b, c, d}};
      },
      rc::gen::inRange<std::uint16_t>(0, codec::kSeqModulo), genAxisEcho(), genAxisEcho(), genPacket(), genPacket(),
      genPacket(), genPacket());
}

}  // namespace ap::test
