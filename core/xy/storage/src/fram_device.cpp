#include "core/xy/storage/fram_device.hpp"

#include <array>

namespace ap::xy_storage {

namespace {
constexpr std::size_t kHeader = 3;  // opcode + 16-bit address, MSB first (the chip's order)
}

bool FramDevice::read(std::uint16_t address, std::span<std::uint8_t> data) const noexcept {
  if (data.size() > kMaxTransfer) return false;
  std::array<std::uint8_t, kHeader + kMaxTransfer> tx{};
  std::array<std::uint8_t, kHeader + kMaxTransfer> rx{};
  tx[0] = opcode::kRead;
  tx[1] = static_cast<std::uint8_t>(address >> 8U);
  tx[2] = static_cast<std::uint8_t>(address & 0xFFU);
  const std::size_t n = kHeader + data.size();
  if (!bus_.transfer(bus_.context, std::span<const std::uint8_t>(tx.data(), n), std::span<std::uint8_t>(rx.data(), n))) {
    return false;
  }
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = rx[kHeader + i];
  return true;
}

bool FramDevice::write(std::uint16_t address, std::span<const std::uint8_t> data) const noexcept {
  if (data.size() > kMaxTransfer) return false;
  std::array<std::uint8_t, 1> wren{opcode::kWren};
  std::array<std::uint8_t, 1> sink{};
  if (!bus_.transfer(bus_.context, wren, sink)) return false;
  std::array<std::uint8_t, kHeader + kMaxTransfer> tx{};
  std::array<std::uint8_t, kHeader + kMaxTransfer> rx{};
  tx[0] = opcode::kWrite;
  tx[1] = static_cast<std::uint8_t>(address >> 8U);
  tx[2] = static_cast<std::uint8_t>(address & 0xFFU);
  for (std::size_t i = 0; i < data.size(); ++i) tx[kHeader + i] = data[i];
  const std::size_t n = kHeader + data.size();
  return bus_.transfer(bus_.context, std::span<const std::uint8_t>(tx.data(), n), std::span<std::uint8_t>(rx.data(), n));
}

std::optional<std::uint8_t> FramDevice::read_status() const noexcept {
  std::array<std::uint8_t, 2> tx{opcode::kRdsr, 0};
  std::array<std::uint8_t, 2> rx{};
  if (!bus_.transfer(bus_.context, tx, rx)) return std::nullopt;
  return rx[1];
}

bool FramDevice::write_status(std::uint8_t value) const noexcept {
  std::array<std::uint8_t, 1> wren{opcode::kWren};
  std::array<std::uint8_t, 1> sink{};
  if (!bus_.transfer(bus_.context, wren, sink)) return false;
  std::array<std::uint8_t, 2> tx{opcode::kWrsr, value};
  std::array<std::uint8_t, 2> rx{};
  return bus_.transfer(bus_.context, tx, rx);
}

}  // namespace ap::xy_storage
