#pragma once
// One FRAM record: the parameter set laid out by the map table, least significant byte first
// (thesis §9.2), followed by the sequence number and a CRC-32 over all preceding bytes.
#include <array>
#include <cstdint>
#include <span>

#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"

namespace ap::xy_storage {

using RecordBytes = std::array<std::uint8_t, kRecordSize>;

// Why a stored copy was not used.
enum class RecordStatus : std::uint8_t {
  Valid,
  BadCrc,        // torn write, bit rot or never written
  BadValue,      // CRC fine but an item out of range or a cross rule broken (incl. layout version)
  Unreadable,    // the SPI transfer reported a bus error
};

struct DecodeResult {
  RecordStatus status;
  ParamId bad_item;  // meaningful for BadValue
  ParameterSet set;  // meaningful for Valid only
  std::uint32_t sequence;
};

// Writes `value` into `out` as `length` bytes, least significant first (two's complement for
// signed items).
constexpr void put_le(std::span<std::uint8_t> out, std::size_t offset, std::size_t length,
                      std::uint32_t value) noexcept {
  for (std::size_t i = 0; i < length; ++i) {
    out[offset + i] = static_cast<std::uint8_t>(value >> (8U * i));
  }
}

constexpr std::uint32_t get_le(std::span<const std::uint8_t> in, std::size_t offset, std::size_t length) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < length; ++i) {
    v |= static_cast<std::uint32_t>(in[offset + i]) << (8U * i);
  }
  return v;
}

// Encodes `set` (assumed valid; the store validates first) with `sequence` and the CRC.
void encode_record(const ParameterSet& set, std::uint32_t sequence, std::span<std::uint8_t, kRecordSize> out) noexcept;

// CRC first, then every item against the table, then the cross rules.
DecodeResult decode_record(std::span<const std::uint8_t, kRecordSize> in) noexcept;

// Serial-number comparison (RFC 1982 style) so a wrapped sequence still orders correctly.
constexpr bool sequence_newer(std::uint32_t a, std::uint32_t b) noexcept {
  const std::uint32_t d = a - b;
  return d != 0U && d < 0x8000'0000U;
}

}  // namespace ap::xy_storage
