// The XY board's port: the core's Hardware interface (core/xy/board) over the peripheral layer
// (firmware/periph.hpp), with the raw-reading conversions of docs/qemu.md "Inputs". The same
// code links into the STM32L476 image and the QEMU image.
#pragma once

#include <cstdint>

#include "core/xy/board/board.hpp"

namespace ap::xy_fw {

xy_board::Hardware board_hardware();
// Bytes the board wrote to the link since the last call.
std::uint16_t take_tx_count();

// Raw readings -> core units (docs/qemu.md "Inputs"). Ranges: every 16-bit code.
// Battery through a 1:2 divider, VREF+ 3.3 V, 16-bit: mV = code * 6600 / 65536, rounded down.
constexpr std::uint16_t battery_mv(std::uint16_t code) {
  return static_cast<std::uint16_t>(std::uint32_t{code} * 6600U / 65536U);
}
// Charge current sense, bidirectional about mid-scale, 1/8 mA per code: mA = (code - 32768) / 8,
// rounded toward minus infinity; charging positive.
constexpr std::int32_t charge_ma(std::uint16_t code) {
  const std::int32_t d = static_cast<std::int32_t>(code) - 32768;
  return d >= 0 ? d / 8 : -((-d + 7) / 8);
}
// RLS Orbis frame: [turns: 16, two's complement][position: 14][error][warning], the two
// status bits active low (the encoder reports a fault by pulling them to 0).
constexpr xy_axis::EncoderReading encoder_reading(const std::uint8_t (&miso)[4]) {
  const auto turns = static_cast<std::int16_t>(static_cast<std::uint16_t>(miso[0] << 8 | miso[1]));
  const auto low = static_cast<std::uint16_t>(miso[2] << 8 | miso[3]);
  xy_axis::EncoderReading r;
  r.turns = turns;
  r.counts = static_cast<std::uint16_t>(low >> 2);
  r.valid = (low & 0x2U) != 0 ? 1 : 0;
  return r;
}

// The GPIO expander (MCP23S17 register map, address 0): GPIOA/GPIOB inputs and OLATB outputs.
inline constexpr std::uint8_t kExpanderRead = 0x41;
inline constexpr std::uint8_t kExpanderWrite = 0x40;
inline constexpr std::uint8_t kExpanderGpioA = 0x12;
inline constexpr std::uint8_t kExpanderOlatB = 0x15;
// Input bits of the 16-bit GPIOA|GPIOB word.
inline constexpr std::uint16_t kExpXMin = 1U << 0, kExpXMax = 1U << 1, kExpYMin = 1U << 2, kExpYMax = 1U << 3;
inline constexpr std::uint16_t kExpButton = 1U << 4, kExpCharger = 1U << 5, kExpUsb = 1U << 6;
inline constexpr std::uint16_t kExpBle1 = 1U << 7, kExpBle2 = 1U << 8;
// Output bits of OLATB: the TMC2130 DRV_ENN pins (active low: 1 = driver off) and the RGB
// LED (1 = lit).
inline constexpr std::uint8_t kOlatEnnX = 1U << 6, kOlatEnnY = 1U << 7;
inline constexpr std::uint8_t kOlatLedR = 1U << 1, kOlatLedG = 1U << 2, kOlatLedB = 1U << 3;
// IODIRB: the MCP23S17 resets every pin to an input (IODIR = 0xFF, datasheet 1.6 / 3.5.1), so
// OLATB drives nothing until these bits are cleared; GPIOB0 (BLE STATUS2) stays an input.
inline constexpr std::uint8_t kExpanderIodirB = 0x01;
inline constexpr std::uint8_t kIodirB = static_cast<std::uint8_t>(
    0xFFU & ~static_cast<unsigned>(kOlatEnnX | kOlatEnnY | kOlatLedR | kOlatLedG | kOlatLedB));

// RLS Orbis programming: unlock bytes, then 'Z' (set the reading of where the shaft stands
// now, kept in the encoder's memory) and the 32-bit count, MSB first (docs/motion.md "Homing
// and the encoder zero").
inline constexpr std::uint8_t kOrbisUnlock[4] = {0xCD, 0xEF, 0x89, 0xAB};
inline constexpr std::uint8_t kOrbisSetPosition = 0x5A;

// Makes the expander's output pins outputs (drivers off, LED dark). Before Board::boot().
void port_init();

}  // namespace ap::xy_fw
