#pragma once
// TMP117 register map and fields (TI SNOSD82D, section 8 "Register Map"; seed-000 §4.17
// names the part). Only what the driver and the device model need.
#include <cstdint>

namespace ap::xy_tmp117 {

// 7-bit addresses by the ADD0 strap (datasheet 7.5.3.1.2). The board's strap is not in the
// thesis; GND (0x48) is the datasheet's first entry and the one seed-000 quotes.
inline constexpr std::uint8_t kAddressGnd = 0x48;
inline constexpr std::uint8_t kAddressVplus = 0x49;
inline constexpr std::uint8_t kAddressSda = 0x4A;
inline constexpr std::uint8_t kAddressScl = 0x4B;

enum class Reg : std::uint8_t {
  TempResult = 0x00,     // R, reset 0x8000 (-256 °C until the first conversion completes)
  Configuration = 0x01,  // R/W, reset 0x0220 (from EEPROM)
  THighLimit = 0x02,     // R/W, reset 0x6000 (192 °C)
  TLowLimit = 0x03,      // R/W, reset 0x8000 (-256 °C)
  EepromUl = 0x04,       // R/W, reset 0x0000
  Eeprom1 = 0x05,
  Eeprom2 = 0x06,
  TempOffset = 0x07,     // R/W, reset 0x0000, same format as TempResult, added to every result
  Eeprom3 = 0x08,
  DeviceId = 0x0F,       // R, 0x0117: Rev[15:12] = 0, DID[11:0] = 0x117
};

constexpr std::uint8_t reg_address(Reg r) { return static_cast<std::uint8_t>(r); }

inline constexpr std::uint16_t kResetTempResult = 0x8000;
inline constexpr std::uint16_t kResetConfiguration = 0x0220;
inline constexpr std::uint16_t kResetTHigh = 0x6000;
inline constexpr std::uint16_t kResetTLow = 0x8000;

// Device_ID: the revision nibble may change between silicon revisions, the DID may not.
inline constexpr std::uint16_t kDeviceIdMask = 0x0FFF;
inline constexpr std::uint16_t kDeviceId = 0x0117;
inline constexpr unsigned kRevisionShift = 12;

// Configuration register fields (datasheet 8.1.2).
namespace cfg {
inline constexpr std::uint16_t kHighAlert = 1u << 15;   // R
inline constexpr std::uint16_t kLowAlert = 1u << 14;    // R
inline constexpr std::uint16_t kDataReady = 1u << 13;   // R, cleared by reading Temp_Result or Configuration
inline constexpr std::uint16_t kEepromBusy = 1u << 12;  // R
inline constexpr unsigned kModShift = 10;               // MOD[1:0]
inline constexpr std::uint16_t kModMask = 0x3u << kModShift;
inline constexpr unsigned kConvShift = 7;               // CONV[2:0]
inline constexpr std::uint16_t kConvMask = 0x7u << kConvShift;
inline constexpr unsigned kAvgShift = 5;                // AVG[1:0]
inline constexpr std::uint16_t kAvgMask = 0x3u << kAvgShift;
inline constexpr std::uint16_t kThermMode = 1u << 4;    // T/nA
inline constexpr std::uint16_t kPolarity = 1u << 3;     // POL
inline constexpr std::uint16_t kDrAlert = 1u << 2;      // DR/Alert pin select
inline constexpr std::uint16_t kSoftReset = 1u << 1;    // always reads 0
// The bits a write stores (bit 0 is reserved, bits 15:12 are status).
inline constexpr std::uint16_t kWritable = kModMask | kConvMask | kAvgMask | kThermMode | kPolarity | kDrAlert;

inline constexpr std::uint16_t kModContinuous = 0;  // 00 (10 also means continuous and reads back 00)
inline constexpr std::uint16_t kModShutdown = 1;
inline constexpr std::uint16_t kModOneShot = 3;

constexpr std::uint16_t mod(std::uint16_t word) { return (word & kModMask) >> kModShift; }
constexpr std::uint16_t conv(std::uint16_t word) { return (word & kConvMask) >> kConvShift; }
constexpr std::uint16_t avg(std::uint16_t word) { return (word & kAvgMask) >> kAvgShift; }
constexpr std::uint16_t make(std::uint16_t mod, std::uint16_t conv, std::uint16_t avg) {
  return static_cast<std::uint16_t>((mod << kModShift) | (conv << kConvShift) | (avg << kAvgShift));
}
}  // namespace cfg

}  // namespace ap::xy_tmp117
