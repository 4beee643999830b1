#pragma once
// The 40-bit SPI datagram (datasheet 4.1): byte 0 is the address with bit 7 set for a write,
// bytes 1..4 the 32 data bits MSB first. The reply's byte 0 is SPI_STATUS; its bytes 1..4
// carry the data latched by the *previous* datagram, which is why a read takes two transfers.
#include <array>
#include <cstdint>

namespace ap::xy_tmc2130 {

using Datagram = std::array<std::uint8_t, 5>;

inline constexpr std::uint8_t kWriteBit = 0x80;
inline constexpr std::uint8_t kAddressMask = 0x7F;

struct Request {
  bool write;
  std::uint8_t address;  // 0..0x7F
  std::uint32_t data;    // ignored by the chip on a read
  friend constexpr bool operator==(const Request&, const Request&) = default;
};

struct SpiStatus {
  bool reset_flag;    // GSTAT.reset: the chip lost its registers since GSTAT was last read
  bool driver_error;  // GSTAT.drv_err: overtemperature or short, the bridge is off
  bool sg2;           // DRV_STATUS.stallGuard
  bool standstill;    // DRV_STATUS.stst
  friend constexpr bool operator==(const SpiStatus&, const SpiStatus&) = default;
};

struct Reply {
  SpiStatus status;
  std::uint32_t data;
};

constexpr Datagram encode(const Request& r) {
  return {static_cast<std::uint8_t>((r.address & kAddressMask) | (r.write ? kWriteBit : 0u)),
          static_cast<std::uint8_t>(r.data >> 24), static_cast<std::uint8_t>(r.data >> 16),
          static_cast<std::uint8_t>(r.data >> 8), static_cast<std::uint8_t>(r.data)};
}

constexpr std::uint32_t data_of(const Datagram& d) {
  return (std::uint32_t{d[1]} << 24) | (std::uint32_t{d[2]} << 16) | (std::uint32_t{d[3]} << 8) |
         std::uint32_t{d[4]};
}

constexpr Request decode_request(const Datagram& d) {
  return {(d[0] & kWriteBit) != 0, static_cast<std::uint8_t>(d[0] & kAddressMask), data_of(d)};
}

constexpr std::uint8_t encode_status(const SpiStatus& s) {
  return static_cast<std::uint8_t>((s.reset_flag ? 1u : 0u) | (s.driver_error ? 2u : 0u) |
                                   (s.sg2 ? 4u : 0u) | (s.standstill ? 8u : 0u));
}

// Bits 4..7 of SPI_STATUS are not defined by the datasheet and are ignored.
constexpr SpiStatus decode_status(std::uint8_t b) {
  return {(b & 1u) != 0, (b & 2u) != 0, (b & 4u) != 0, (b & 8u) != 0};
}

constexpr Reply decode_reply(const Datagram& d) { return {decode_status(d[0]), data_of(d)}; }

}  // namespace ap::xy_tmc2130
