#pragma once
// RapidCheck generators for valid frames, drawn from the codec tables so that a new table
// entry is covered without touching the tests.
#include <rapidcheck.h>

#include <string>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "core/xy/frame/frames.hpp"

namespace ap::test {

inline rc::Gen<xy_frame::AxisCommand> genAxisCommand() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, xy_codec::kCommandCount), [](std::size_t i) {
    const auto& info = xy_codec::kCommands[i];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1),
                        [id = info.id](std::int32_t d) { return xy_frame::AxisCommand{id, d}; });
  });
}

inline rc::Gen<xy_frame::SubscriberSlot> genSlot() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, xy_codec::kSubscriberCount), [](std::size_t i) {
    const auto& info = xy_codec::kSubscribers[i];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.arg_range.min, info.arg_range.max + 1),
                        [id = info.id](std::int32_t a) { return xy_frame::SubscriberSlot{id, static_cast<std::uint8_t>(a)}; });
  });
}

inline rc::Gen<xy_frame::CommandFrame> genCommand() {
  return rc::gen::apply(
      [](std::uint16_t seq, xy_frame::AxisCommand x, xy_frame::AxisCommand y, xy_frame::SubscriberSlot a, xy_frame::SubscriberSlot b,
         xy_frame::SubscriberSlot c, xy_frame::SubscriberSlot d) {
        return xy_frame::CommandFrame{seq, x, y, {a, b, c, d}};
      },
      rc::gen::inRange<std::uint16_t>(0, xy_codec::kSeqModulo), genAxisCommand(), genAxisCommand(), genSlot(), genSlot(),
      genSlot(), genSlot());
}

inline rc::Gen<xy_frame::AxisEcho> genAxisEcho() {
  return rc::gen::mapcat(rc::gen::inRange<std::size_t>(0, xy_codec::kStatusCount), [](std::size_t i) {
    const auto& info = xy_codec::kStatuses[i];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1),
                        [id = info.id](std::int32_t d) { return xy_frame::AxisEcho{id, d}; });
  });
}

inline rc::Gen<xy_frame::SubscriberPacket> genPacket() {
  return rc::gen::mapcat(genSlot(), [](xy_frame::SubscriberSlot s) {
    const auto& info = xy_codec::kSubscribers[static_cast<std::size_t>(s.id)];
    return rc::gen::map(rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1),
                        [s](std::int32_t d) { return xy_frame::SubscriberPacket{s, d}; });
  });
}

inline rc::Gen<xy_frame::EchoFrame> genEcho() {
  return rc::gen::apply(
      [](std::uint16_t seq, xy_frame::AxisEcho x, xy_frame::AxisEcho y, xy_frame::SubscriberPacket a, xy_frame::SubscriberPacket b,
         xy_frame::SubscriberPacket c, xy_frame::SubscriberPacket d) {
        return xy_frame::EchoFrame{seq, x, y, {a, b, c, d}};
      },
      rc::gen::inRange<std::uint16_t>(0, xy_codec::kSeqModulo), genAxisEcho(), genAxisEcho(), genPacket(), genPacket(),
      genPacket(), genPacket());
}

}  // namespace ap::test
