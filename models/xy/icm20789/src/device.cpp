#include "models/xy/icm20789/device.hpp"

#include <algorithm>
#include <array>

namespace ap::model::xy_icm20789 {

namespace r = chip::reg;

Device::Device(std::uint8_t address) : address_(address) { power_on_reset(); }

void Device::power_on_reset() {
  regs_.fill(0);
  regs_[r::kPwrMgmt1] = chip::kResetPwrMgmt1;
  regs_[r::kConfig] = chip::kResetConfig;
  regs_[r::kWhoAmI] = chip::kWhoAmIValue;
  pointer_ = 0;
}

bool Device::awake() const {
  const std::uint8_t p = regs_[r::kPwrMgmt1];
  // CLKSEL = 7 stops the clock (DS-000169 PWR_MGMT_1).
  return (p & chip::bits::kSleep) == 0 && (p & chip::bits::kClkselMask) != 7;
}

namespace {
// Stated here from the datasheet, not taken from core/xy/icm20789 (a firmware that misread them
// must not find the model agreeing): DS-000169 GYRO_CONFIG (0x1B) FS_SEL = bits 4:3, and
// Table 1's gyro sensitivity per FS_SEL, in tenths of an LSB per °/s: 131, 65.5, 32.8, 16.4.
constexpr unsigned kFsSelShift = 3;
constexpr std::uint8_t kFsSelMask = 0x18;
constexpr std::array<std::int32_t, 4> kTenthLsbPerDps{1310, 655, 328, 164};
}  // namespace

chip::FullScale Device::full_scale() const {
  return static_cast<chip::FullScale>((regs_[r::kGyroConfig] & kFsSelMask) >> kFsSelShift);
}

std::int16_t Device::code_for_mdps(std::int32_t mdps, chip::FullScale fs) {
  // code = mdps / 1000 * tenths / 10, nearest, halves away from zero, then the ADC's limits.
  const std::int64_t n = std::int64_t{mdps} * kTenthLsbPerDps[static_cast<std::size_t>(fs) & 3U];
  const std::int64_t d = std::int64_t{10'000};
  const std::int64_t a = n < 0 ? -n : n;
  const std::int64_t q = a / d + ((a % d) * 2 >= d ? 1 : 0);
  return static_cast<std::int16_t>(std::clamp<std::int64_t>(n < 0 ? -q : q, -32768, 32767));
}

bool Device::read_only(std::uint8_t reg) {
  // INT_STATUS and the sensor outputs, FIFO count, WHO_AM_I.
  return (reg >= 0x3A && reg <= 0x48) || reg == 0x72 || reg == 0x73 || reg == r::kWhoAmI;
}

void Device::refresh_outputs() {
  if (!awake() || (regs_[r::kPwrMgmt2] & chip::bits::kDisableZg) != 0) return;
  const std::int16_t code = exact_code_ ? code_ : code_for_mdps(rate_mdps_, full_scale());
  const auto u = static_cast<std::uint16_t>(code);
  regs_[r::kGyroZoutH] = static_cast<std::uint8_t>(u >> 8);
  regs_[r::kGyroZoutL] = static_cast<std::uint8_t>(u & 0xFFu);
}

void Device::write_register(std::uint8_t reg, std::uint8_t v) {
  if (read_only(reg)) return;  // acknowledged and dropped
  if (reg == r::kPwrMgmt1 && (v & chip::bits::kDeviceReset) != 0) {
    // DEVICE_RESET: every register back to its reset value; the bit clears itself.
    const std::uint8_t who = regs_[r::kWhoAmI];
    power_on_reset();
    regs_[r::kWhoAmI] = who;
    return;
  }
  regs_[reg] = v;
}

bus::Status Device::transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  if (address != address_) return bus::Status::AddressNack;
  if (!tx.empty()) {
    // model: a register pointer past the map (bit 7 set) is refused.
    if ((tx[0] & 0x80u) != 0) return bus::Status::DataNack;
    pointer_ = tx[0];
    for (std::size_t i = 1; i < tx.size(); ++i) {
      write_register(pointer_, tx[i]);
      pointer_ = static_cast<std::uint8_t>((pointer_ + 1u) & 0x7Fu);  // model: wraps at the map's end
    }
  }
  if (!rx.empty()) {
    // One sample for the whole burst, so _H and _L always belong together.
    refresh_outputs();
    for (auto& b : rx) {
      b = regs_[pointer_];
      pointer_ = static_cast<std::uint8_t>((pointer_ + 1u) & 0x7Fu);
    }
  }
  return bus::Status::Ok;
}

}  // namespace ap::model::xy_icm20789
