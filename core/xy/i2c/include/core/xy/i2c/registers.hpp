#pragma once
// Register access for devices with an 8-bit register pointer written first (TMP117,
// ICM-20789): a write is pointer + data in one transaction, a read is pointer, repeated
// START, data. The out-parameters are written only when the transaction completed, so a
// failed read can never hand a driver half a register.
#include <cstdint>
#include <span>

#include "core/xy/i2c/port.hpp"

namespace ap::xy_i2c {

// Registers up to this many bytes fit one transaction here (a 16-bit word, a gyro axis pair).
inline constexpr std::size_t kMaxRegisterBytes = 8;

Status write_u8(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint8_t value);
Status read_u8(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint8_t& out);

// 16-bit registers sent most significant byte first (TMP117 datasheet 7.5.3.1.3; the
// ICM-20789's *_H / *_L pairs read as one burst).
Status write_u16be(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint16_t value);
Status read_u16be(const Port& port, std::uint8_t address, std::uint8_t reg, std::uint16_t& out);

// `out.size()` consecutive registers from `reg` (auto-increment), at most kMaxRegisterBytes;
// a longer request is refused with BusError before any traffic.
Status read_burst(const Port& port, std::uint8_t address, std::uint8_t reg, std::span<std::uint8_t> out);

}  // namespace ap::xy_i2c
