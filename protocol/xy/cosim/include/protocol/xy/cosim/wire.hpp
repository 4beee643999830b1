// The co-simulation channel (docs/qemu.md): the second UART of the QEMU image, between its
// peripheral layer and the host process that runs the device models. The image is the only
// side that starts an exchange; the host answers requests and grants ticks, so everything the
// image sees arrives at a point fixed by the tick count, never by wall-clock timing, and the
// same scenario gives the same trace twice.
//
// A message is [kind][length][length payload bytes]; multi-byte fields are big-endian.
// Header-only and heap-free: the image and the host include the same definitions.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ap::xy_cosim {

inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kMaxPayload = 255;

enum class Kind : std::uint8_t {
  // image -> host
  Hello = 'H',      // [version]: reset handler done, about to boot the board core
  Spi = 'S',        // [device][MOSI bytes]: full-duplex transfer, answered by Reply [MISO bytes]
  I2c = 'I',        // [address][n_read][write bytes]: answered by Reply [status][n_read bytes],
                    // status an ap::xy_i2c::Status (0 ok, 2 address NACK, 3 data NACK, 4 bus error)
  Adc = 'A',        // [channel]: one conversion, answered by Reply [code hi][code lo]
  PinRead = 'p',    // [pin]: answered by Reply [level]
  PinWrite = 'P',   // [pin][level]
  Step = 'T',       // [axis][psc hi][psc lo][arr hi][arr lo][steps: 4]: the step timer armed for this tick
  Ready = 'W',      // []: waiting for the next tick grant
  Done = 'D',       // [tick: 4][TX bytes this tick: 2][x pos: 4][y pos: 4]
  Report = 'R',     // [stack bytes used: 4][stack size: 4][ticks: 4]: answer to End
  Fault = 'F',      // [exception number][pc: 4][lr: 4][cfsr: 4][hfsr: 4]: the image stopped
  // host -> image
  Reply = 'r',
  Grant = 'G',      // [tick: 4][frame bytes delivered since power-up: 4]
  End = 'E',        // []: report and stop
};

// The image's own stops, in a Fault message's exception byte beside the core's exception
// numbers (1..15, interrupts 16..97); the board's fault record (docs/qemu.md) uses the same.
namespace stop {
inline constexpr std::uint8_t kStackPaint = 0xFF;         // the thread stack's last painted word was overwritten
inline constexpr std::uint8_t kChannel = 0xFE;            // the co-simulation channel broke
inline constexpr std::uint8_t kClock = 0xFD;              // the STM32L476's clock tree did not start
inline constexpr std::uint8_t kStackRanOut = 0xFC;        // a fault's frame could not be stacked: pc = the stack pointer
inline constexpr std::uint8_t kHandlerStackPaint = 0xFB;  // the exception stack's last painted word was overwritten
}  // namespace stop

// Devices on the board's SPI buses (chip selects, docs/qemu.md "Peripherals").
enum class SpiDevice : std::uint8_t { TmcX = 0, TmcY = 1, Fram = 2, EncoderX = 3, EncoderY = 4, Expander = 5 };
inline constexpr std::uint8_t kSpiDevices = 6;

// ADC channels: battery through its divider, the charge-current sense (docs/qemu.md).
enum class AdcChannel : std::uint8_t { Battery = 0, ChargeCurrent = 1 };

// MCU pins the peripheral layer drives or reads directly (the rest sit on the GPIO expander).
// KillSwitch: high cuts the unit's supply (thesis §7.9.5); ChargerEnable: high connects the
// charging circuit (§7.9.3; docs/board.md "Charger disconnect").
enum class Pin : std::uint8_t {
  DirX = 0, DirY = 1, EnaX = 2, EnaY = 3, BleStatus1 = 4, BleStatus2 = 5, KillSwitch = 6, ChargerEnable = 7
};
inline constexpr std::uint8_t kPins = 8;

constexpr void put_u16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v);
}
constexpr void put_u32(std::uint8_t* p, std::uint32_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 24);
  p[1] = static_cast<std::uint8_t>(v >> 16);
  p[2] = static_cast<std::uint8_t>(v >> 8);
  p[3] = static_cast<std::uint8_t>(v);
}
constexpr std::uint16_t get_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(static_cast<unsigned>(p[0]) << 8 | p[1]);
}
constexpr std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | p[3];
}

}  // namespace ap::xy_cosim
