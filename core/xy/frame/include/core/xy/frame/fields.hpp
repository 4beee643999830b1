#pragma once
// Fixed-width ASCII field readers and writers shared by the command and echo codecs.
// Readers never write their output on failure, so a rejected frame changes nothing.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/xy/frame/frames.hpp"

namespace ap::xy_frame::fields {

using Bytes = std::span<const std::uint8_t>;
using Out = std::span<std::uint8_t>;

// Unsigned decimal of `width` digits (width <= 6). nullopt names the first bad byte in *bad.
std::optional<std::uint32_t> read_digits(Bytes frame, std::size_t offset, std::size_t width, std::size_t* bad);
// Six-character data field: "000000".."999999" or "-00001".."-99999".
std::optional<std::int32_t> read_data(Bytes frame, std::size_t offset, std::size_t* bad);
// Four upper-case hex characters.
std::optional<std::uint16_t> read_hex16(Bytes frame, std::size_t offset, std::size_t* bad);

// Writers: value must fit (callers validate first).
void write_digits(Out frame, std::size_t offset, std::size_t width, std::uint32_t value);
void write_data(Out frame, std::size_t offset, std::int32_t value);
void write_hex16(Out frame, std::size_t offset, std::uint16_t value);

// CRC of bytes [1, crc_offset): everything between the start character and the CRC field.
std::uint16_t payload_crc(Bytes frame, std::size_t crc_offset);

}  // namespace ap::xy_frame::fields
