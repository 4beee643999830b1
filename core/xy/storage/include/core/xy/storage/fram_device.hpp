#pragma once
// The SPI side: a narrow, allocation-free transport (function pointer + context) and a thin
// driver that speaks the MB85RS/FM25 opcode set over it. The board layer binds the transport
// to its SPI peripheral and chip-select pin; tests bind it to the FRAM model.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/xy/storage/fram_map.hpp"

namespace ap::xy_storage {

namespace opcode {
inline constexpr std::uint8_t kWren = 0x06;
inline constexpr std::uint8_t kWrdi = 0x04;
inline constexpr std::uint8_t kRdsr = 0x05;
inline constexpr std::uint8_t kWrsr = 0x01;
inline constexpr std::uint8_t kRead = 0x03;
inline constexpr std::uint8_t kWrite = 0x02;
}  // namespace opcode

// Status register bits of the MB85RS256B.
namespace status {
inline constexpr std::uint8_t kWel = 0x02;
inline constexpr std::uint8_t kBp0 = 0x04;
inline constexpr std::uint8_t kBp1 = 0x08;
inline constexpr std::uint8_t kWpen = 0x80;
}  // namespace status

// One chip-select-framed transaction: CS low, clock tx[i] out and store MISO in rx[i] for
// every i, CS high. tx and rx have equal length. Returns false on a bus error (e.g. a HAL
// timeout); the driver then treats the operation as failed.
struct SpiBus {
  using Transfer = bool (*)(void* context, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept;
  Transfer transfer;
  void* context;
};

// Largest single READ/WRITE payload; one record is always moved in one transaction so a
// power cut tears it at most once.
inline constexpr std::size_t kMaxTransfer = kRecordSize;

class FramDevice {
 public:
  explicit constexpr FramDevice(SpiBus bus) noexcept : bus_(bus) {}

  // Reads data.size() (<= kMaxTransfer) bytes from address. False on a bus error.
  bool read(std::uint16_t address, std::span<std::uint8_t> data) const noexcept;
  // WREN then WRITE. False on a bus error; the caller verifies by reading back, because the
  // part acknowledges nothing (a protected block or a dead chip drops the write silently).
  bool write(std::uint16_t address, std::span<const std::uint8_t> data) const noexcept;
  std::optional<std::uint8_t> read_status() const noexcept;
  bool write_status(std::uint8_t value) const noexcept;

 private:
  SpiBus bus_;
};

}  // namespace ap::xy_storage
