#pragma once
// A TMC2130 as seen from its SPI pins, for tests and the simulated board. It follows the
// datasheet, not the driver: pipelined replies, write-only registers that read as 0,
// GSTAT cleared by a read, the SPI_STATUS byte, unimplemented bits dropped, power-on reset,
// and the power stage: a STEP edge turns the motor only when the chopper is on (CHOPCONF.TOFF
// != 0) and DRV_ENN is low, by the microstep the chip's own CHOPCONF.MRES selects. The bit
// positions the power stage reads are written here from the datasheet, not taken from the
// firmware's register table, so a firmware that misreads them cannot agree with the model.
// The same holds for every register's access class, reset value and implemented bits: they
// come from the model's own datasheet table (datasheet.hpp), not from core/xy/tmc2130/regmap.hpp;
// chip::Reg is used only as an SPI address in the public API (its value is the address).
// Test hooks (fault injection, access log) are explicit and off by default.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/xy/tmc2130/datagram.hpp"
#include "core/xy/tmc2130/driver.hpp"
#include "core/xy/tmc2130/regmap.hpp"
#include "models/xy/tmc2130/datasheet.hpp"

namespace ap::model::xy_tmc2130 {

namespace chip = ap::xy_tmc2130;

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
  std::uint32_t chip_register(chip::Reg reg) const {
    return reg == chip::Reg::DRV_STATUS ? drv_status_view() : regs_[slot(reg)];
  }

  // The DRV_ENN pin (datasheet 2.2, pin table: "high: power stage switched off, all motor
  // outputs floating"). The board drives it from the MCU's enable output.
  void set_drv_enn(bool high) { drv_enn_high_ = high; }

  // Datasheet 5.5, CHOPCONF bits 3..0 TOFF: "%0000: driver disable, all bridges off"; and
  // DRV_ENN above. Off, the motor is not driven: STEP edges are ignored.
  bool power_stage_on() const;

  // Microsteps per full step for one STEP edge: datasheet 5.5, CHOPCONF bits 27..24 MRES,
  // %0000 = 256 (native) ... %1000 = 1 (full step); 256 >> MRES. The reset value 0 gives 256.
  std::int32_t microsteps() const;

  // `edges` STEP rising edges in the direction `dir` (+1/-1): how far the rotor turns, in
  // 1/256 of a full step (datasheet, STEP/DIR interface: one microstep per active STEP edge,
  // with dedge = 0 the rising one; MRES = 0 is 256 microsteps per full step). Zero while the power stage is off.
  std::int64_t step(std::int64_t edges, int dir);

  // Time passing on the chip's clock (the standstill detection and the current reduction
  // count it). The internal oscillator's nominal 12 MHz (datasheet, electrical
  // characteristics, from memory).
  void elapse_us(std::int64_t us);

  // Standstill (datasheet 5.5 DRV_STATUS.stst): 2^20 clocks after the last STEP edge.
  bool standstill() const;
  // The current scale the chip drives now (DRV_STATUS.CS_ACTUAL, datasheet 5.2 IHOLD_IRUN,
  // TPOWERDOWN): IRUN while stepping; TPOWERDOWN * 2^18 clocks after the last edge it starts
  // to fall by one step per IHOLDDELAY * 2^18 clocks (at once with IHOLDDELAY = 0) to IHOLD;
  // 0 while the power stage is off.
  std::int32_t current_scale() const;

  // The diagnostic outputs (datasheet 5.1 GCONF diag0_* / diag1_*, 2.2 pin table), as "asserted":
  // DIAG0 on a driver error (ot, s2ga, s2gb) with diag0_error, on the over-temperature
  // pre-warning with diag0_otpw, on a stall with diag0_stall; DIAG1 on a stall with
  // diag1_stall. Open drain, active low unless the push-pull bit is set (then active high).
  bool diag0_asserted() const;
  bool diag1_asserted() const;
  // The pin level: low when asserted (open drain, active low) unless the push-pull bit is set.
  bool diag0_level() const;
  bool diag1_level() const;

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

  // The register contents, indexed by the 7-bit SPI address (unused addresses stay 0).
  static constexpr std::size_t kAddressCount = 0x80;
  static constexpr std::uint8_t slot(chip::Reg reg) {
    return static_cast<std::uint8_t>(chip::address(reg) & std::uint8_t{0x7F});
  }
  std::array<std::uint32_t, kAddressCount> regs_{};
  std::uint32_t latch_ = 0;
  bool drv_enn_high_ = false;
  // A short to ground (s2ga/s2gb) switches the bridges off until TOFF is written 0 or DRV_ENN
  // goes high (datasheet 5.5 DRV_STATUS s2ga/s2gb).
  bool short_latched_ = false;
  // Clocks since the last STEP edge; power-up counts as long ago (the reset DRV_STATUS has stst).
  std::int64_t clocks_since_step_ = std::int64_t{1} << 40;
  std::uint32_t drv_status_input_ = 0x80000000U;  // set_input's flags (ot, s2g*, stallGuard, ...)
  std::uint32_t drv_status_view() const;
  chip::Reg corrupt_reg_ = chip::Reg::GCONF;
  std::uint32_t corrupt_flip_ = 0;
  unsigned corrupt_count_ = 0;
  unsigned power_cycle_in_ = 0;
  std::vector<Access> log_;
};

}  // namespace ap::model::xy_tmc2130
