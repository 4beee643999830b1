#pragma once
// The ICM-20789's 6-axis part as seen from its I2C pins (TDK DS-000169), for tests and the
// simulated board: 128 byte-wide registers behind an auto-incrementing register pointer,
// power-up values (asleep, PWR_MGMT_1 = 0x41, WHO_AM_I = 0x03, CONFIG = 0x80), read-only
// sensor and identity registers ignoring writes, DEVICE_RESET, and the z-rate output
// GYRO_ZOUT at the configured full scale while the chip is awake (asleep, or with the z gyro
// in standby, the output registers keep their last value). Not modelled: accelerometer,
// temperature, FIFO, interrupts, the DLPF's dynamics and start-up time, the pressure sensor
// (its own address, 0x63). Where the datasheet is silent the model chooses (marked "model:"),
// listed in docs/sensors.md.
#include <array>
#include <cstdint>
#include <span>

#include "core/xy/icm20789/registers.hpp"
#include "core/xy/icm20789/rotation.hpp"
#include "models/xy/i2c/bus.hpp"

namespace ap::model::xy_icm20789 {

namespace chip = ap::xy_icm20789;
namespace bus = ap::xy_i2c;

class Device : public ap::model::xy_i2c::Device {
 public:
  explicit Device(std::uint8_t address = chip::kAddressAd0Low);

  bus::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx,
                       std::span<std::uint8_t> rx) override;

  void power_on_reset();

  // What the gyro measures about z, in m°/s; the code is the nearest one at the present full
  // scale (halves away from zero), saturated at -32768 / 32767 like the ADC.
  void set_rate_mdps(std::int32_t mdps) {
    rate_mdps_ = mdps;
    exact_code_ = false;
  }
  // Test hook: GYRO_ZOUT shows exactly `code` while awake, whatever the full scale.
  void set_rate_code(std::int16_t code) {
    code_ = code;
    exact_code_ = true;
  }
  // Test hook: a different part at the same address.
  void set_who_am_i(std::uint8_t v) { regs_[chip::reg::kWhoAmI] = v; }

  std::uint8_t reg(std::uint8_t r) const { return regs_[r & 0x7Fu]; }
  bool awake() const;
  chip::FullScale full_scale() const;
  std::uint8_t address() const { return address_; }

  static std::int16_t code_for_mdps(std::int32_t mdps, chip::FullScale fs);

 private:
  static bool read_only(std::uint8_t r);
  void write_register(std::uint8_t r, std::uint8_t v);
  void refresh_outputs();

  std::uint8_t address_;
  std::uint8_t pointer_ = 0;
  std::array<std::uint8_t, 128> regs_{};
  std::int32_t rate_mdps_ = 0;
  std::int16_t code_ = 0;
  bool exact_code_ = false;
};

}  // namespace ap::model::xy_icm20789
