#include "core/xy/frame/echo_codec.hpp"

#include "core/xy/frame/frame_codec.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::xy_frame {

namespace c = ap::xy_codec;

namespace {

// What an echo adds to the shared skeleton: status ids, and subscriber packets (the slot
// the command asked for, then its data).
struct EchoSpec {
  using Frame = EchoFrame;
  using AxisId = c::EchoStatus;
  static constexpr std::size_t kLength = c::kEchoLength;
  static constexpr char kStart = c::kEchoStart;
  static constexpr std::size_t kCrcOffset = c::kEchoCrcOffset;
  static constexpr std::size_t kEndOffset = c::kEchoEndOffset;
  static constexpr std::size_t kFieldWidth = c::kPacketWidth;
  static constexpr c::FrameError kUnknownAxisId = c::FrameError::UnknownStatus;

  static AxisId id_of(const AxisEcho& a) { return a.status; }
  static AxisEcho make_axis(AxisId id, std::int32_t data) { return {id, data}; }
  static const c::StatusInfo* find_axis(std::uint32_t id) { return c::find_status(id); }

  static bool read_field(std::span<const std::uint8_t> b, std::size_t o, SubscriberPacket& p, std::size_t* bad) {
    SubscriberSlot s;
    if (!slot::read(b, o, s, bad)) return false;
    const auto data = fields::read_data(b, o + c::kSlotWidth, bad);
    if (!data) return false;
    p = {s, *data};
    return true;
  }
  static void write_field(std::span<std::uint8_t> out, std::size_t o, const SubscriberPacket& p) {
    slot::write(out, o, p.slot);
    fields::write_data(out, o + c::kSlotWidth, p.data);
  }
  static Rejection check_field(const SubscriberPacket& p, std::size_t o) {
    if (auto r = slot::check(p.slot, o); !r.ok()) return r;
    const auto* info = c::find_subscriber(static_cast<std::uint32_t>(p.slot.id));  // known: checked above
    if (info != nullptr && !info->range.contains(p.data)) {
      return {c::FrameError::DataOutOfRange, static_cast<std::uint16_t>(o + c::kSlotWidth)};
    }
    return {};
  }
};

using Codec = FrameCodec<EchoSpec>;

}  // namespace

Rejection validate(const EchoFrame& f) { return Codec::check(f); }
Rejection parse_echo(std::span<const std::uint8_t> b, EchoFrame& out) { return Codec::parse(b, out); }
Rejection format_echo(const EchoFrame& f, EchoBytes out) { return Codec::format(f, out); }

}  // namespace ap::xy_frame
