#pragma once
// CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, not reflected, xorout 0x0000, check 0x29B1.
// Chosen because its Hamming distance is 4 far beyond our 59-byte payloads (every 1-, 2- and
// 3-bit error is caught) and a bitwise form needs no table in flash.
#include <cstddef>
#include <cstdint>
#include <span>

namespace ap::xy_codec {

inline constexpr std::uint16_t kCrcPoly = 0x1021;
inline constexpr std::uint16_t kCrcInit = 0xFFFF;
inline constexpr std::uint16_t kCrcCheck = 0x29B1;  // published check value over "123456789"

constexpr std::uint16_t crc16_update(std::uint16_t crc, std::uint8_t byte) {
  crc = static_cast<std::uint16_t>(crc ^ static_cast<std::uint16_t>(byte << 8));
  for (int bit = 0; bit < 8; ++bit) {
    const bool top = (crc & 0x8000U) != 0;
    crc = static_cast<std::uint16_t>(crc << 1);
    if (top) crc = static_cast<std::uint16_t>(crc ^ kCrcPoly);
  }
  return crc;
}

constexpr std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  std::uint16_t crc = kCrcInit;
  for (const std::uint8_t b : bytes) crc = crc16_update(crc, b);
  return crc;
}

}  // namespace ap::xy_codec
