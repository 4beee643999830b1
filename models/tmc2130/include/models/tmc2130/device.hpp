#pragma once
// A TMC2130 as seen from its SPI pins, for tests and the simulated board. It follows the
// datasheet, not the driver: pipelined replies, write-only registers that read as 0,
// GSTAT cleared by a read, the SPI_STATUS byte, unimplemented bits dropped, power-on reset.
// Test hooks (fault injection, access log) are explicit and off by default.
#include <array>
#include <cstdint>
#include <vector>

#include "core/tmc2130/datagram.hpp"
#include "core/tmc2130/driver.hpp"
#include "core/tmc2130/regmap.hpp"

namespace ap::model::tmc2130 {

namespace chip = ap::tmc2130;

class Device {
 public:
  Device() { power_cycle(); }

  // One 40-bit transfer, MOSI in, MISO out.
  chip::Datagram transfer(const chip::Datagram& mosi);

  // Supply loss and return (motor power cycled while the MCU stayed up): every register
  // back to its reset value, GSTAT.reset set, the latch cleared.
  void power_cycle();

  // What the chip really holds, write-only registers included (a test oracle: the driver
  // cannot see this).
  std::uint32_t chip_register(chip::Reg reg) const { return regs_[chip::index_of(reg)]; }

  // Inputs the chip would measure: read-only registers (DRV_STATUS, TSTEP, ...) and GSTAT
  // flags such as drv_err.
  void set_input(chip::Reg reg, std::uint32_t value);

  // Fault injection: the chip loses power again after `transfers` more transfers
  // (a supply that bounces); 0 disarms.
  void power_cycle_after(unsigned transfers) { power_cycle_in_ = transfers; }

  // Fault injection: the next `count` writes to `reg` store the value XOR `flip` (a bad
  // bit on MOSI), so read-back verification sees a mismatch.
  void corrupt_writes(chip::Reg reg, std::uint32_t flip, unsigned count);

  struct Access {
    bool write;
    std::uint8_t address;
    std::uint32_t data;
  };
  const std::vector<Access>& log() const { return log_; }
  void clear_log() { log_.clear(); }
  unsigned reads_of(chip::Reg reg) const;
  unsigned writes_of(chip::Reg reg) const;

  // Adapter for chip::SpiPort: context is a Device*.
  static bool spi(void* context, const chip::Datagram& tx, chip::Datagram& rx);
  chip::SpiPort port() { return {&Device::spi, this}; }

 private:
  std::uint32_t read_view(std::uint8_t addr) const;
  std::uint8_t status_byte() const;

  std::array<std::uint32_t, chip::kRegisterCount> regs_{};
  std::uint32_t latch_ = 0;
  chip::Reg corrupt_reg_ = chip::Reg::GCONF;
  std::uint32_t corrupt_flip_ = 0;
  unsigned corrupt_count_ = 0;
  unsigned power_cycle_in_ = 0;
  std::vector<Access> log_;
};

}  // namespace ap::model::tmc2130
