#include "core/frame/echo_codec.hpp"

#include "protocol/codec/statuses.hpp"
#include "protocol/codec/subscribers.hpp"
#include "core/frame/fields.hpp"

namespace ap::frame {

namespace c = ap::codec;

namespace {

constexpr std::size_t packet_offset(std::size_t i) { return c::kSubsOffset + i * c::kPacketWidth; }

Rejection reject(c::FrameError e, std::size_t offset) { return {e, static_cast<std::uint16_t>(offset)}; }

Rejection validate_axis(const AxisEcho& a, std::size_t id_offset, std::size_t data_offset) {
  const auto* info = c::find_status(static_cast<std::uint32_t>(a.status));
  if (info == nullptr) return reject(c::FrameError::UnknownStatus, id_offset);
  if (!info->range.contains(a.data)) return reject(c::FrameError::DataOutOfRange, data_offset);
  return {};
}

}  // namespace

Rejection validate(const EchoFrame& f) {
  if (f.seq >= c::kSeqModulo) return reject(c::FrameError::DataOutOfRange, c::kSeqOffset);
  if (auto r = validate_axis(f.x, c::kXIdOffset, c::kXDataOffset); !r.ok()) return r;
  if (auto r = validate_axis(f.y, c::kYIdOffset, c::kYDataOffset); !r.ok()) return r;
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const auto& p = f.subs[i];
    const auto* info = c::find_subscriber(static_cast<std::uint32_t>(p.slot.id));
    if (info == nullptr) return reject(c::FrameError::UnknownSubscriber, packet_offset(i));
    if (!info->arg_range.contains(p.slot.arg)) return reject(c::FrameError::ArgOutOfRange, packet_offset(i) + c::kSubIdWidth);
    if (!info->range.contains(p.data)) return reject(c::FrameError::DataOutOfRange, packet_offset(i) + c::kSlotWidth);
  }
  return {};
}

Rejection parse_echo(std::span<const std::uint8_t> b, EchoFrame& out) {
  if (b.size() != c::kEchoLength) {
    return reject(c::FrameError::BadLength, b.size() < c::kEchoLength ? b.size() : c::kEchoLength);
  }
  if (b[0] != static_cast<std::uint8_t>(c::kEchoStart)) return reject(c::FrameError::BadStart, 0);
  if (b[c::kEchoEndOffset] != static_cast<std::uint8_t>(c::kEnd)) return reject(c::FrameError::BadEnd, c::kEchoEndOffset);
  std::size_t bad = 0;
  const auto bad_char = [&bad] { return reject(c::FrameError::BadChar, bad); };
  EchoFrame f;
  const auto seq = fields::read_digits(b, c::kSeqOffset, c::kSeqWidth, &bad);
  if (!seq) return bad_char();
  f.seq = static_cast<std::uint16_t>(*seq);
  const auto xid = fields::read_digits(b, c::kXIdOffset, c::kIdWidth, &bad);
  if (!xid) return bad_char();
  const auto xdata = fields::read_data(b, c::kXDataOffset, &bad);
  if (!xdata) return bad_char();
  const auto yid = fields::read_digits(b, c::kYIdOffset, c::kIdWidth, &bad);
  if (!yid) return bad_char();
  const auto ydata = fields::read_data(b, c::kYDataOffset, &bad);
  if (!ydata) return bad_char();
  f.x = {static_cast<c::EchoStatus>(*xid), *xdata};
  f.y = {static_cast<c::EchoStatus>(*yid), *ydata};
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const std::size_t o = packet_offset(i);
    const auto id = fields::read_digits(b, o, c::kSubIdWidth, &bad);
    if (!id) return bad_char();
    const auto arg = fields::read_digits(b, o + c::kSubIdWidth, c::kSubArgWidth, &bad);
    if (!arg) return bad_char();
    const auto data = fields::read_data(b, o + c::kSlotWidth, &bad);
    if (!data) return bad_char();
    f.subs[i] = {{static_cast<c::SubscriberId>(*id), static_cast<std::uint8_t>(*arg)}, *data};
  }
  const auto crc = fields::read_hex16(b, c::kEchoCrcOffset, &bad);
  if (!crc) return bad_char();
  if (*crc != fields::payload_crc(b, c::kEchoCrcOffset)) return reject(c::FrameError::BadCrc, c::kEchoCrcOffset);
  if (auto r = validate(f); !r.ok()) return r;
  out = f;
  return {};
}

Rejection format_echo(const EchoFrame& f, EchoBytes out) {
  if (auto r = validate(f); !r.ok()) return r;
  out[0] = static_cast<std::uint8_t>(c::kEchoStart);
  fields::write_digits(out, c::kSeqOffset, c::kSeqWidth, f.seq);
  fields::write_digits(out, c::kXIdOffset, c::kIdWidth, static_cast<std::uint32_t>(f.x.status));
  fields::write_data(out, c::kXDataOffset, f.x.data);
  fields::write_digits(out, c::kYIdOffset, c::kIdWidth, static_cast<std::uint32_t>(f.y.status));
  fields::write_data(out, c::kYDataOffset, f.y.data);
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const std::size_t o = packet_offset(i);
    fields::write_digits(out, o, c::kSubIdWidth, static_cast<std::uint32_t>(f.subs[i].slot.id));
    fields::write_digits(out, o + c::kSubIdWidth, c::kSubArgWidth, f.subs[i].slot.arg);
    fields::write_data(out, o + c::kSlotWidth, f.subs[i].data);
  }
  fields::write_hex16(out, c::kEchoCrcOffset, fields::payload_crc(out, c::kEchoCrcOffset));
  out[c::kEchoEndOffset] = static_cast<std::uint8_t>(c::kEnd);
  return {};
}

}  // namespace ap::frame
