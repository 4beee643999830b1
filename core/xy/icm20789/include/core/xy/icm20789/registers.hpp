#pragma once
// ICM-20789 6-axis part: the registers the driver touches (TDK DS-000169 rev. 1.4, section 14
// "Register Map" and 15 "Register Descriptions"; seed-000 §4.15 names the part). The pressure
// sensor behind the same pins has its own address (0x63) and is not used.
#include <cstdint>

namespace ap::xy_icm20789 {

// 7-bit address by the AD0 pin (datasheet 11.2). The board's strap is not in the thesis.
inline constexpr std::uint8_t kAddressAd0Low = 0x68;
inline constexpr std::uint8_t kAddressAd0High = 0x69;

namespace reg {
inline constexpr std::uint8_t kSmplrtDiv = 0x19;   // 25: ODR = internal rate / (1 + div)
inline constexpr std::uint8_t kConfig = 0x1A;      // 26: FIFO_MODE[6], EXT_SYNC_SET[5:3], DLPF_CFG[2:0]
inline constexpr std::uint8_t kGyroConfig = 0x1B;  // 27: XG/YG/ZG_ST[7:5], FS_SEL[4:3], FCHOICE_B[1:0]
inline constexpr std::uint8_t kGyroXoutH = 0x43;   // 67..72: X, Y, Z as big-endian int16
inline constexpr std::uint8_t kGyroZoutH = 0x47;   // 71
inline constexpr std::uint8_t kGyroZoutL = 0x48;   // 72
inline constexpr std::uint8_t kPwrMgmt1 = 0x6B;    // 107: DEVICE_RESET[7], SLEEP[6], CLKSEL[2:0]
inline constexpr std::uint8_t kPwrMgmt2 = 0x6C;    // 108: accel / gyro axis standby
inline constexpr std::uint8_t kWhoAmI = 0x75;      // 117
}  // namespace reg

inline constexpr std::uint8_t kWhoAmIValue = 0x03;

// Reset values that differ from 0x00 (register-map note of DS-000169).
inline constexpr std::uint8_t kResetPwrMgmt1 = 0x41;  // asleep, CLKSEL = 1
inline constexpr std::uint8_t kResetConfig = 0x80;    // bit 7 reserved

namespace bits {
inline constexpr std::uint8_t kDeviceReset = 0x80;  // PWR_MGMT_1
inline constexpr std::uint8_t kSleep = 0x40;        // PWR_MGMT_1
inline constexpr std::uint8_t kClkselMask = 0x07;   // PWR_MGMT_1
inline constexpr std::uint8_t kDlpfCfgMask = 0x07;  // CONFIG
inline constexpr std::uint8_t kFsSelShift = 3;      // GYRO_CONFIG
inline constexpr std::uint8_t kFsSelMask = 0x18;
inline constexpr std::uint8_t kFchoiceBMask = 0x03;
inline constexpr std::uint8_t kDisableZg = 0x01;    // PWR_MGMT_2
}  // namespace bits

}  // namespace ap::xy_icm20789
