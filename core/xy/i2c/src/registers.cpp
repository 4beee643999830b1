#include "core/xy/i2c/registers.hpp"

#include <array>

namespace ap::xy_i2c {

Status write_u8(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint8_t value) {
  const std::array<std::uint8_t, 2> tx{reg, value};
  return transfer(port, address, tx, {});
}

Status read_u8(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint8_t& out) {
  std::array<std::uint8_t, 1> rx{};
  const auto s = read_burst(port, address, reg, rx);
  if (s == Status::Ok) out = rx[0];
  return s;
}

Status write_u16be(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint16_t value) {
  const std::array<std::uint8_t, 3> tx{reg, static_cast<std::uint8_t>(value >> 8),
                                       static_cast<std::uint8_t>(value & 0xFFu)};
  return transfer(port, address, tx, {});
}

Status read_u16be(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint16_t& out) {
  std::array<std::uint8_t, 2> rx{};
  const auto s = read_burst(port, address, reg, rx);
  if (s == Status::Ok) out = static_cast<std::uint16_t>((unsigned{rx[0]} << 8) | rx[1]);
  return s;
}

Status read_burst(const Port& port, std::uint8_t address, std::uint8_t reg, std::span<std::uint8_t> out) {
  if (out.size() > kMaxRegisterBytes) return Status::BusError;
  // Into a local buffer first: a controller that fails half-way may have filled some bytes.
  std::array<std::uint8_t, kMaxRegisterBytes> rx{};
  const std::array<std::uint8_t, 1> tx{reg};
  const auto s = transfer(port, address, tx, std::span<std::uint8_t>(rx.data(), out.size()));
  if (s != Status::Ok) return s;
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = rx[i];
  return s;
}

}  // namespace ap::xy_i2c
