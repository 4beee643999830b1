#pragma once
// The one skeleton of both frame codecs. A command and an echo share their layout
// (docs/protocol.md): start character, seq, X id + data, Y id + data, a fixed number of
// subscriber fields, CRC-16 over everything between start and CRC, end character. They
// differ only in the start character, the length, what an axis id means (command or status)
// and how wide a subscriber field is (slot, or slot + data). A Spec names those differences:
//
//   using Frame; using AxisId;            the frame struct and the axis id enum
//   kLength, kStart, kCrcOffset, kEndOffset, kFieldWidth
//   AxisId axis_id(axis) / axis.data      read through id_of() and make_axis()
//   find_axis(id) -> info with .range     the table of the axis ids
//   read_field / write_field / check_field   one subscriber field
//
// decode() is the link layer (syntax and CRC only), check() the table checks; parse =
// decode + check, format = check + encode, so a bad frame is never written nor accepted.
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/xy/frame/fields.hpp"
#include "core/xy/frame/frames.hpp"
#include "protocol/xy/codec/layout.hpp"

namespace ap::xy_frame {

// One subscriber slot (id + argument), the field a command carries and the head of the packet
// an echo carries; the readers leave `s` untouched on failure.
namespace slot {
bool read(std::span<const std::uint8_t> b, std::size_t at, SubscriberSlot& s, std::size_t* bad);
void write(std::span<std::uint8_t> out, std::size_t at, const SubscriberSlot& s);
// Known id and argument in range; the offset names the bad field.
Rejection check(const SubscriberSlot& s, std::size_t at);
}  // namespace slot

template <class Spec>
struct FrameCodec {
  using Frame = typename Spec::Frame;

  static constexpr std::size_t field_offset(std::size_t i) { return xy_codec::kSubsOffset + i * Spec::kFieldWidth; }
  static Rejection reject(xy_codec::FrameError e, std::size_t offset) { return {e, static_cast<std::uint16_t>(offset)}; }

  // Checks in wire order: length, start, end, characters, CRC. On error `out` is untouched.
  static Rejection decode(std::span<const std::uint8_t> b, Frame& out) {
    if (b.size() != Spec::kLength) {
      return reject(xy_codec::FrameError::BadLength, b.size() < Spec::kLength ? b.size() : Spec::kLength);
    }
    if (b[0] != static_cast<std::uint8_t>(Spec::kStart)) return reject(xy_codec::FrameError::BadStart, 0);
    if (b[Spec::kEndOffset] != static_cast<std::uint8_t>(xy_codec::kEnd)) {
      return reject(xy_codec::FrameError::BadEnd, Spec::kEndOffset);
    }
    std::size_t bad = 0;
    Frame f;
    const auto seq = fields::read_digits(b, xy_codec::kSeqOffset, xy_codec::kSeqWidth, &bad);
    if (!seq) return reject(xy_codec::FrameError::BadChar, bad);
    f.seq = static_cast<std::uint16_t>(*seq);
    if (!read_axis(b, xy_codec::kXIdOffset, xy_codec::kXDataOffset, f.x, &bad) ||
        !read_axis(b, xy_codec::kYIdOffset, xy_codec::kYDataOffset, f.y, &bad)) {
      return reject(xy_codec::FrameError::BadChar, bad);
    }
    for (std::size_t i = 0; i < f.subs.size(); ++i) {
      if (!Spec::read_field(b, field_offset(i), f.subs[i], &bad)) return reject(xy_codec::FrameError::BadChar, bad);
    }
    const auto crc = fields::read_hex16(b, Spec::kCrcOffset, &bad);
    if (!crc) return reject(xy_codec::FrameError::BadChar, bad);
    if (*crc != fields::payload_crc(b, Spec::kCrcOffset)) return reject(xy_codec::FrameError::BadCrc, Spec::kCrcOffset);
    out = f;
    return {};
  }

  // Table checks only (ids known, data and arguments in range, seq < 1000); the offset
  // names the field that would carry the bad value.
  static Rejection check(const Frame& f) {
    if (f.seq >= xy_codec::kSeqModulo) return reject(xy_codec::FrameError::DataOutOfRange, xy_codec::kSeqOffset);
    if (auto r = check_axis(f.x, xy_codec::kXIdOffset, xy_codec::kXDataOffset); !r.ok()) return r;
    if (auto r = check_axis(f.y, xy_codec::kYIdOffset, xy_codec::kYDataOffset); !r.ok()) return r;
    for (std::size_t i = 0; i < f.subs.size(); ++i) {
      if (auto r = Spec::check_field(f.subs[i], field_offset(i)); !r.ok()) return r;
    }
    return {};
  }

  static Rejection parse(std::span<const std::uint8_t> b, Frame& out) {
    Frame f;
    if (auto r = decode(b, f); !r.ok()) return r;
    if (auto r = check(f); !r.ok()) return r;
    out = f;
    return {};
  }

  // Writes all kLength bytes, or nothing when check() fails.
  static Rejection format(const Frame& f, std::span<std::uint8_t, Spec::kLength> out) {
    if (auto r = check(f); !r.ok()) return r;
    out[0] = static_cast<std::uint8_t>(Spec::kStart);
    fields::write_digits(out, xy_codec::kSeqOffset, xy_codec::kSeqWidth, f.seq);
    write_axis(out, xy_codec::kXIdOffset, xy_codec::kXDataOffset, f.x);
    write_axis(out, xy_codec::kYIdOffset, xy_codec::kYDataOffset, f.y);
    for (std::size_t i = 0; i < f.subs.size(); ++i) Spec::write_field(out, field_offset(i), f.subs[i]);
    fields::write_hex16(out, Spec::kCrcOffset, fields::payload_crc(out, Spec::kCrcOffset));
    out[Spec::kEndOffset] = static_cast<std::uint8_t>(xy_codec::kEnd);
    return {};
  }

 private:
  template <class Axis>
  static bool read_axis(std::span<const std::uint8_t> b, std::size_t id_at, std::size_t data_at, Axis& a, std::size_t* bad) {
    const auto id = fields::read_digits(b, id_at, xy_codec::kIdWidth, bad);
    if (!id) return false;
    const auto data = fields::read_data(b, data_at, bad);
    if (!data) return false;
    a = Spec::make_axis(static_cast<typename Spec::AxisId>(*id), *data);
    return true;
  }
  template <class Axis>
  static void write_axis(std::span<std::uint8_t> out, std::size_t id_at, std::size_t data_at, const Axis& a) {
    fields::write_digits(out, id_at, xy_codec::kIdWidth, static_cast<std::uint32_t>(Spec::id_of(a)));
    fields::write_data(out, data_at, a.data);
  }
  template <class Axis>
  static Rejection check_axis(const Axis& a, std::size_t id_at, std::size_t data_at) {
    const auto* info = Spec::find_axis(static_cast<std::uint32_t>(Spec::id_of(a)));
    if (info == nullptr) return reject(Spec::kUnknownAxisId, id_at);
    if (!info->range.contains(a.data)) return reject(xy_codec::FrameError::DataOutOfRange, data_at);
    return {};
  }
};

}  // namespace ap::xy_frame
