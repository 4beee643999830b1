#include "core/xy/frame/fields.hpp"

#include "protocol/xy/codec/crc16.hpp"
#include "protocol/xy/codec/layout.hpp"

namespace ap::xy_frame::fields {

namespace {
constexpr bool is_digit(std::uint8_t c) { return c >= '0' && c <= '9'; }
}  // namespace

std::optional<std::uint32_t> read_digits(Bytes frame, std::size_t offset, std::size_t width, std::size_t* bad) {
  std::uint32_t value = 0;  // width <= 6, so value < 10^6
  for (std::size_t i = 0; i < width; ++i) {
    const std::uint8_t c = frame[offset + i];
    if (!is_digit(c)) {
      *bad = offset + i;
      return std::nullopt;
    }
    value = value * 10U + static_cast<std::uint32_t>(c - '0');
  }
  return value;
}

std::optional<std::int32_t> read_data(Bytes frame, std::size_t offset, std::size_t* bad) {
  if (frame[offset] == '-') {
    const auto magnitude = read_digits(frame, offset + 1, xy_codec::kDataWidth - 1, bad);
    if (!magnitude) return std::nullopt;
    if (*magnitude == 0) {  // "-00000": a second spelling of zero
      *bad = offset;
      return std::nullopt;
    }
    return -static_cast<std::int32_t>(*magnitude);
  }
  const auto value = read_digits(frame, offset, xy_codec::kDataWidth, bad);
  if (!value) return std::nullopt;
  return static_cast<std::int32_t>(*value);
}

std::optional<std::uint16_t> read_hex16(Bytes frame, std::size_t offset, std::size_t* bad) {
  std::uint16_t value = 0;
  for (std::size_t i = 0; i < xy_codec::kCrcWidth; ++i) {
    const std::uint8_t c = frame[offset + i];
    std::uint16_t nibble = 0;
    if (is_digit(c)) {
      nibble = static_cast<std::uint16_t>(c - '0');
    } else if (c >= 'A' && c <= 'F') {
      nibble = static_cast<std::uint16_t>(c - 'A' + 10);
    } else {
      *bad = offset + i;
      return std::nullopt;
    }
    value = static_cast<std::uint16_t>((value << 4) | nibble);
  }
  return value;
}

void write_digits(Out frame, std::size_t offset, std::size_t width, std::uint32_t value) {
  for (std::size_t i = width; i > 0; --i) {
    frame[offset + i - 1] = static_cast<std::uint8_t>('0' + value % 10U);
    value /= 10U;
  }
}

void write_data(Out frame, std::size_t offset, std::int32_t value) {
  if (value < 0) {
    frame[offset] = '-';
    write_digits(frame, offset + 1, xy_codec::kDataWidth - 1, static_cast<std::uint32_t>(-value));
  } else {
    write_digits(frame, offset, xy_codec::kDataWidth, static_cast<std::uint32_t>(value));
  }
}

void write_hex16(Out frame, std::size_t offset, std::uint16_t value) {
  constexpr char kHex[] = "0123456789ABCDEF";
  for (std::size_t i = 0; i < xy_codec::kCrcWidth; ++i) {
    const auto shift = 12U - 4U * static_cast<unsigned>(i);
    frame[offset + i] = static_cast<std::uint8_t>(kHex[(value >> shift) & 0xFU]);
  }
}

std::uint16_t payload_crc(Bytes frame, std::size_t crc_offset) {
  return xy_codec::crc16(frame.subspan(xy_codec::kStartWidth, crc_offset - xy_codec::kStartWidth));
}

}  // namespace ap::xy_frame::fields
