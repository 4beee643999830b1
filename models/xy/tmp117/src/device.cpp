#include "models/xy/tmp117/device.hpp"

#include <algorithm>

namespace ap::model::xy_tmp117 {

namespace {
constexpr std::size_t idx(chip::Reg r) { return static_cast<std::size_t>(r); }
// SNOSD82 8.1.2 (Configuration register): bits 11:2 are read/write (MOD 11:10, CONV 9:7,
// AVG 6:5, T/nA 4, POL 3, DR/Alert 2); 15:12 are status (read only), 1 is the soft reset
// (reads 0), 0 is reserved. Stated here, not taken from the driver's mask.
constexpr std::uint16_t kConfigWritable = 0x0FFCU;
constexpr std::uint16_t kStatusBits = chip::cfg::kHighAlert | chip::cfg::kLowAlert | chip::cfg::kDataReady |
                                      chip::cfg::kEepromBusy;
// model: factory contents of the general-purpose EEPROM words (the datasheet gives xxxx).
constexpr std::uint16_t kFactoryEeprom1 = 0x1A2B;
constexpr std::uint16_t kFactoryEeprom2 = 0x3C4D;
constexpr std::uint16_t kFactoryEeprom3 = 0x5E6F;
}  // namespace

Device::Device(std::uint8_t address) : address_(address) { power_on_reset(); }

void Device::power_on_reset() {
  regs_.fill(0);
  regs_[idx(chip::Reg::TempResult)] = chip::kResetTempResult;
  regs_[idx(chip::Reg::Configuration)] = chip::kResetConfiguration;
  regs_[idx(chip::Reg::THighLimit)] = chip::kResetTHigh;
  regs_[idx(chip::Reg::TLowLimit)] = chip::kResetTLow;
  regs_[idx(chip::Reg::Eeprom1)] = kFactoryEeprom1;
  regs_[idx(chip::Reg::Eeprom2)] = kFactoryEeprom2;
  regs_[idx(chip::Reg::Eeprom3)] = kFactoryEeprom3;
  pointer_ = 0;
  restart_conversions();
}

std::uint32_t Device::active_us(unsigned avg) {
  static constexpr std::array<std::uint32_t, 4> kActive{15'500, 125'000, 500'000, 1'000'000};
  return kActive[avg & 3u];
}

std::uint32_t Device::cycle_us(unsigned conv, unsigned avg) {
  // Table 7-7: the cycle is the CONV standby period, but never shorter than the averaging.
  static constexpr std::array<std::uint32_t, 8> kConv{15'500, 125'000, 250'000, 500'000,
                                                      1'000'000, 4'000'000, 8'000'000, 16'000'000};
  return std::max(kConv[conv & 7u], active_us(avg));
}

std::uint16_t Device::code_for_mc(std::int32_t mc) {
  // code = mc * 128 / 1000 = mc * 16 / 125, nearest, halves away from zero.
  const std::int64_t n = std::int64_t{mc} * 16;
  const std::int64_t a = n < 0 ? -n : n;
  const std::int64_t q = a / 125 + ((a % 125) * 2 >= 125 ? 1 : 0);
  const std::int64_t code = std::clamp<std::int64_t>(n < 0 ? -q : q, -32768, 32767);
  return static_cast<std::uint16_t>(code);
}

void Device::set_result_code(std::uint16_t code) {
  regs_[idx(chip::Reg::TempResult)] = code;
  regs_[idx(chip::Reg::Configuration)] |= chip::cfg::kDataReady;
}

void Device::restart_conversions() {
  const std::uint16_t c = regs_[idx(chip::Reg::Configuration)];
  const unsigned mod = chip::cfg::mod(c);
  if (mod == chip::cfg::kModShutdown) {
    next_done_us_.reset();
  } else {
    next_done_us_ = now_us_ + active_us(chip::cfg::avg(c));
  }
}

void Device::complete_conversion() {
  const std::int64_t offset = static_cast<std::int16_t>(regs_[idx(chip::Reg::TempOffset)]);
  const std::int64_t raw = static_cast<std::int16_t>(code_for_mc(temperature_mc_));
  regs_[idx(chip::Reg::TempResult)] = static_cast<std::uint16_t>(std::clamp<std::int64_t>(raw + offset, -32768, 32767));
  std::uint16_t& c = regs_[idx(chip::Reg::Configuration)];
  c |= chip::cfg::kDataReady;
  ++conversions_;
  if (chip::cfg::mod(c) == chip::cfg::kModOneShot) {
    // One-shot: back to shutdown after the conversion (datasheet 7.4.3).
    c = static_cast<std::uint16_t>((c & ~chip::cfg::kModMask) | (chip::cfg::kModShutdown << chip::cfg::kModShift));
    next_done_us_.reset();
  } else {
    *next_done_us_ += cycle_us(chip::cfg::conv(c), chip::cfg::avg(c));
  }
}

void Device::advance_us(std::uint64_t us) {
  const std::uint64_t end = now_us_ + us;
  while (next_done_us_ && *next_done_us_ <= end) {
    now_us_ = *next_done_us_;
    complete_conversion();
  }
  now_us_ = end;
}

std::uint16_t Device::reg(chip::Reg r) const {
  if (r == chip::Reg::DeviceId) return device_id_;
  return regs_[idx(r)];
}

bool Device::pointer_valid(std::uint8_t p) const { return p <= 0x08 || p == 0x0F; }

std::uint16_t Device::read_register(std::uint8_t p) {
  if (p == chip::reg_address(chip::Reg::DeviceId)) return device_id_;
  const std::uint16_t v = regs_[p];
  if (p == chip::reg_address(chip::Reg::TempResult) || p == chip::reg_address(chip::Reg::Configuration)) {
    regs_[idx(chip::Reg::Configuration)] &= static_cast<std::uint16_t>(~chip::cfg::kDataReady);
  }
  return v;
}

void Device::write_register(std::uint8_t p, std::uint16_t value) {
  switch (static_cast<chip::Reg>(p)) {
    case chip::Reg::TempResult:
    case chip::Reg::DeviceId:
      return;  // read-only: the write is acknowledged and dropped
    case chip::Reg::Configuration: {
      std::uint16_t& c = regs_[p];
      const std::uint16_t before = c & (chip::cfg::kModMask | chip::cfg::kConvMask | chip::cfg::kAvgMask);
      std::uint16_t next = static_cast<std::uint16_t>((c & kStatusBits) | (value & kConfigWritable));
      if (chip::cfg::mod(next) == 2) next &= static_cast<std::uint16_t>(~chip::cfg::kModMask);  // 10 reads as 00
      c = next;
      if ((value & chip::cfg::kSoftReset) != 0) {
        power_on_reset();
        return;
      }
      // model: a change of mode, cycle or averaging starts a fresh conversion.
      if ((c & (chip::cfg::kModMask | chip::cfg::kConvMask | chip::cfg::kAvgMask)) != before ||
          chip::cfg::mod(c) == chip::cfg::kModOneShot) {
        restart_conversions();
      }
      return;
    }
    case chip::Reg::EepromUl:
      regs_[p] = value & 0x8000u;  // EUN; bit 14 (busy) is read-only
      return;
    default:
      regs_[p] = value;
      return;
  }
}

bus::Status Device::transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  if (address != address_) return bus::Status::AddressNack;
  // model: only a bare pointer (1 byte) or pointer + one word (3 bytes) is a write the
  // device takes; anything else, or a pointer to no register, is refused and changes nothing.
  if (!tx.empty()) {
    if ((tx.size() != 1 && tx.size() != 3) || !pointer_valid(tx[0])) return bus::Status::DataNack;
    pointer_ = tx[0];
    if (tx.size() == 3) write_register(pointer_, static_cast<std::uint16_t>((tx[1] << 8) | tx[2]));
  }
  if (!rx.empty()) {
    const std::uint16_t v = read_register(pointer_);
    for (std::size_t i = 0; i < rx.size(); ++i) {
      // model: bytes past the word read as a released bus.
      rx[i] = i == 0 ? static_cast<std::uint8_t>(v >> 8) : i == 1 ? static_cast<std::uint8_t>(v & 0xFF) : 0xFF;
    }
  }
  return bus::Status::Ok;
}

}  // namespace ap::model::xy_tmp117
