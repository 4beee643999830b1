#include "core/frame/command_codec.hpp"

#include "protocol/codec/commands.hpp"
#include "protocol/codec/subscribers.hpp"
#include "core/frame/fields.hpp"

namespace ap::frame {

namespace c = ap::codec;

namespace {

constexpr std::size_t slot_offset(std::size_t i) { return c::kSubsOffset + i * c::kSlotWidth; }

Rejection reject(c::FrameError e, std::size_t offset) { return {e, static_cast<std::uint16_t>(offset)}; }

Rejection validate_axis(const AxisCommand& a, std::size_t id_offset, std::size_t data_offset) {
  const auto* info = c::find_command(static_cast<std::uint32_t>(a.id));
  if (info == nullptr) return reject(c::FrameError::UnknownCommand, id_offset);
  if (!info->range.contains(a.data)) return reject(c::FrameError::DataOutOfRange, data_offset);
  return {};
}

}  // namespace

Rejection validate(const CommandFrame& f) {
  if (f.seq >= c::kSeqModulo) return reject(c::FrameError::DataOutOfRange, c::kSeqOffset);
  if (auto r = validate_axis(f.x, c::kXIdOffset, c::kXDataOffset); !r.ok()) return r;
  if (auto r = validate_axis(f.y, c::kYIdOffset, c::kYDataOffset); !r.ok()) return r;
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const auto* info = c::find_subscriber(static_cast<std::uint32_t>(f.subs[i].id));
    if (info == nullptr) return reject(c::FrameError::UnknownSubscriber, slot_offset(i));
    if (!info->arg_range.contains(f.subs[i].arg)) {
      return reject(c::FrameError::ArgOutOfRange, slot_offset(i) + c::kSubIdWidth);
    }
  }
  return {};
}

Rejection decode_command(std::span<const std::uint8_t> b, CommandFrame& out) {
  if (b.size() != c::kCommandLength) {
    return reject(c::FrameError::BadLength, b.size() < c::kCommandLength ? b.size() : c::kCommandLength);
  }
  if (b[0] != static_cast<std::uint8_t>(c::kCommandStart)) return reject(c::FrameError::BadStart, 0);
  if (b[c::kCommandEndOffset] != static_cast<std::uint8_t>(c::kEnd)) {
    return reject(c::FrameError::BadEnd, c::kCommandEndOffset);
  }
  std::size_t bad = 0;
  const auto bad_char = [&bad] { return reject(c::FrameError::BadChar, bad); };
  CommandFrame f;
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
  f.x = {static_cast<c::CommandId>(*xid), *xdata};
  f.y = {static_cast<c::CommandId>(*yid), *ydata};
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    const auto id = fields::read_digits(b, slot_offset(i), c::kSubIdWidth, &bad);
    if (!id) return bad_char();
    const auto arg = fields::read_digits(b, slot_offset(i) + c::kSubIdWidth, c::kSubArgWidth, &bad);
    if (!arg) return bad_char();
    f.subs[i] = {static_cast<c::SubscriberId>(*id), static_cast<std::uint8_t>(*arg)};
  }
  const auto crc = fields::read_hex16(b, c::kCommandCrcOffset, &bad);
  if (!crc) return bad_char();
  if (*crc != fields::payload_crc(b, c::kCommandCrcOffset)) return reject(c::FrameError::BadCrc, c::kCommandCrcOffset);
  out = f;
  return {};
}

Rejection parse_command(std::span<const std::uint8_t> b, CommandFrame& out) {
  CommandFrame f;
  if (auto r = decode_command(b, f); !r.ok()) return r;
  if (auto r = validate(f); !r.ok()) return r;
  out = f;
  return {};
}

Rejection format_command(const CommandFrame& f, CommandBytes out) {
  if (auto r = validate(f); !r.ok()) return r;
  out[0] = static_cast<std::uint8_t>(c::kCommandStart);
  fields::write_digits(out, c::kSeqOffset, c::kSeqWidth, f.seq);
  fields::write_digits(out, c::kXIdOffset, c::kIdWidth, static_cast<std::uint32_t>(f.x.id));
  fields::write_data(out, c::kXDataOffset, f.x.data);
  fields::write_digits(out, c::kYIdOffset, c::kIdWidth, static_cast<std::uint32_t>(f.y.id));
  fields::write_data(out, c::kYDataOffset, f.y.data);
  for (std::size_t i = 0; i < f.subs.size(); ++i) {
    fields::write_digits(out, slot_offset(i), c::kSubIdWidth, static_cast<std::uint32_t>(f.subs[i].id));
    fields::write_digits(out, slot_offset(i) + c::kSubIdWidth, c::kSubArgWidth, f.subs[i].arg);
  }
  fields::write_hex16(out, c::kCommandCrcOffset, fields::payload_crc(out, c::kCommandCrcOffset));
  out[c::kCommandEndOffset] = static_cast<std::uint8_t>(c::kEnd);
  return {};
}

}  // namespace ap::frame
