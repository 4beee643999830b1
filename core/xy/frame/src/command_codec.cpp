#include "core/xy/frame/command_codec.hpp"

#include "core/xy/frame/frame_codec.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::xy_frame {

namespace c = ap::xy_codec;

namespace {

// What a command frame adds to the shared skeleton: command ids, and subscriber slots
// (id + argument) without data.
struct CommandSpec {
  using Frame = CommandFrame;
  using AxisId = c::CommandId;
  static constexpr std::size_t kLength = c::kCommandLength;
  static constexpr char kStart = c::kCommandStart;
  static constexpr std::size_t kCrcOffset = c::kCommandCrcOffset;
  static constexpr std::size_t kEndOffset = c::kCommandEndOffset;
  static constexpr std::size_t kFieldWidth = c::kSlotWidth;
  static constexpr c::FrameError kUnknownAxisId = c::FrameError::UnknownCommand;

  static AxisId id_of(const AxisCommand& a) { return a.id; }
  static AxisCommand make_axis(AxisId id, std::int32_t data) { return {id, data}; }
  static const c::CommandInfo* find_axis(std::uint32_t id) { return c::find_command(id); }

  static bool read_field(std::span<const std::uint8_t> b, std::size_t o, SubscriberSlot& s, std::size_t* bad) {
    return slot::read(b, o, s, bad);
  }
  static void write_field(std::span<std::uint8_t> out, std::size_t o, const SubscriberSlot& s) { slot::write(out, o, s); }
  static Rejection check_field(const SubscriberSlot& s, std::size_t o) { return slot::check(s, o); }
};

using Codec = FrameCodec<CommandSpec>;

}  // namespace

namespace slot {

bool read(std::span<const std::uint8_t> b, std::size_t at, SubscriberSlot& s, std::size_t* bad) {
  const auto id = fields::read_digits(b, at, c::kSubIdWidth, bad);
  if (!id) return false;
  const auto arg = fields::read_digits(b, at + c::kSubIdWidth, c::kSubArgWidth, bad);
  if (!arg) return false;
  s = {static_cast<c::SubscriberId>(*id), static_cast<std::uint8_t>(*arg)};
  return true;
}

void write(std::span<std::uint8_t> out, std::size_t at, const SubscriberSlot& s) {
  fields::write_digits(out, at, c::kSubIdWidth, static_cast<std::uint32_t>(s.id));
  fields::write_digits(out, at + c::kSubIdWidth, c::kSubArgWidth, s.arg);
}

Rejection check(const SubscriberSlot& s, std::size_t at) {
  const auto* info = c::find_subscriber(static_cast<std::uint32_t>(s.id));
  if (info == nullptr) return {c::FrameError::UnknownSubscriber, static_cast<std::uint16_t>(at)};
  if (!info->arg_range.contains(s.arg)) return {c::FrameError::ArgOutOfRange, static_cast<std::uint16_t>(at + c::kSubIdWidth)};
  return {};
}

}  // namespace slot

Rejection validate(const CommandFrame& f) { return Codec::check(f); }
Rejection decode_command(std::span<const std::uint8_t> b, CommandFrame& out) { return Codec::decode(b, out); }
Rejection parse_command(std::span<const std::uint8_t> b, CommandFrame& out) { return Codec::parse(b, out); }
Rejection format_command(const CommandFrame& f, CommandBytes out) { return Codec::format(f, out); }

}  // namespace ap::xy_frame
