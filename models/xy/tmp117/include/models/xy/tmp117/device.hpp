#pragma once
// A TMP117 as seen from its I2C pins (TI SNOSD82D), for tests and the simulated board. It
// follows the datasheet, not the driver: the pointer register, 16-bit registers MSB first,
// power-up values (Temp_Result 0x8000 until the first conversion), read-only registers
// ignoring writes, Data_Ready cleared by reading Temp_Result or Configuration, MOD = 10
// reading back as 00, Soft_Reset, the conversion cycle of Table 7-7 in continuous, shutdown
// and one-shot modes, Temp_Offset added to every result. Not modelled: alert / therm flags
// and the ALERT pin, EEPROM programming (EEPROM registers are plain storage), SMBus alert
// response, general-call reset. Where the datasheet is silent the model chooses (marked
// "model:") and docs/sensors.md lists the choice.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "core/xy/tmp117/registers.hpp"
#include "models/xy/i2c/bus.hpp"

namespace ap::model::xy_tmp117 {

namespace chip = ap::xy_tmp117;
namespace bus = ap::xy_i2c;

class Device : public ap::model::xy_i2c::Device {
 public:
  explicit Device(std::uint8_t address = chip::kAddressGnd);

  bus::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx,
                       std::span<std::uint8_t> rx) override;

  // Power-on / soft reset: registers from the (factory) EEPROM, Temp_Result = 0x8000,
  // continuous conversion restarts.
  void power_on_reset();

  // What the sensor measures. Each completed conversion stores the code nearest to it
  // (halves away from zero) plus Temp_Offset, saturated to int16.
  void set_temperature_mc(std::int32_t mc) { temperature_mc_ = mc; }
  // Test hook: Temp_Result shows `code` now, as if a conversion had just stored it.
  void set_result_code(std::uint16_t code);
  // Test hook: the silicon revision nibble (the DID stays 0x117), or a whole foreign ID.
  void set_device_id(std::uint16_t id) { device_id_ = id; }

  // Simulated time in µs; conversions complete as Table 7-7 says.
  void advance_us(std::uint64_t us);
  void advance_ms(std::uint64_t ms) { advance_us(ms * 1000u); }

  // Oracles the driver cannot see.
  std::uint16_t reg(chip::Reg r) const;
  unsigned conversions() const { return conversions_; }
  std::uint8_t address() const { return address_; }

  static std::uint16_t code_for_mc(std::int32_t mc);
  static std::uint32_t active_us(unsigned avg);
  static std::uint32_t cycle_us(unsigned conv, unsigned avg);

 private:
  bool pointer_valid(std::uint8_t p) const;
  void write_register(std::uint8_t p, std::uint16_t value);
  std::uint16_t read_register(std::uint8_t p);
  void restart_conversions();
  void complete_conversion();

  std::uint8_t address_;
  std::uint8_t pointer_ = 0;
  std::array<std::uint16_t, 16> regs_{};
  std::uint16_t device_id_ = chip::kDeviceId;
  std::int32_t temperature_mc_ = 25000;
  std::uint64_t now_us_ = 0;
  std::optional<std::uint64_t> next_done_us_;
  unsigned conversions_ = 0;
};

}  // namespace ap::model::xy_tmp117
