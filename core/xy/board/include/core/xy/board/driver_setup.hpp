#pragma once
// What the board writes into each TMC2130 at power-up, beyond the chip's reset values: the
// thesis (§7.7.1) initialises the microsteps, the motor current, the diag pins' modes and the
// StallGuard, CoolStep and SpreadCycle parameters. The chip's reset CHOPCONF has TOFF = 0,
// which keeps the power stage off (datasheet 5.5, CHOPCONF.TOFF "%0000: driver disable, all
// bridges off"): a board that skips this does not turn a motor. Each value and its reason is
// in docs/tmc2130.md "Boot configuration"; the test states the expected register words from
// that table, not from these constants.
#include <cstdint>

#include "core/xy/storage/parameters.hpp"
#include "core/xy/tmc2130/driver.hpp"

namespace ap::xy_board {

// SpreadCycle chopper with the datasheet's "getting started" timing (TOFF 3, HSTRT 4, HEND 1,
// TBL 2 = 36 clocks); StallGuard2 needs SpreadCycle, so stealthChop (GCONF.en_pwm_mode) stays
// off. The chip interpolates the chosen microsteps to 256 (intpol).
struct ChopperSetup {
  std::int64_t toff = 3;
  std::int64_t hstrt = 4;
  std::int64_t hend = 1;
  std::int64_t tbl = 2;
  std::int64_t chm = 0;     // 0: SpreadCycle
  std::int64_t vsense = 0;  // 0: 0.32 V full scale (docs/tmc2130.md, current equation)
  std::int64_t intpol = 1;
};
inline constexpr ChopperSetup kChopper{};

// DIAG0 reports driver errors and the over-temperature pre-warning, DIAG1 a stall (the
// StallGuard homing input), both open collector, active low (GCONF bits 5, 6, 8; 12, 13 = 0).
struct DiagSetup {
  std::int64_t diag0_error = 1;
  std::int64_t diag0_otpw = 1;
  std::int64_t diag1_stall = 1;
};
inline constexpr DiagSetup kDiag{};

// Standstill: the current falls from IRUN to IHOLD over IHOLDDELAY * 2^18 clocks, starting
// TPOWERDOWN * 2^18 clocks after the last STEP (the datasheet's example values 6 and 10).
inline constexpr std::int64_t kIholdDelay = 6;
inline constexpr std::int64_t kTpowerdown = 10;
// StallGuard2's status (and DIAG1) is valid only while TSTEP <= TCOOLTHRS: the widest value
// enables it at every speed; CoolStep stays off (COOLCONF.semin = 0), decision in docs.
inline constexpr std::int64_t kTcoolthrs = 0xFFFFF;

// MRES encodes 256 >> MRES microsteps; storage admits only powers of two in [1, 256].
std::int64_t mres_of(std::uint16_t microsteps);

// Writes GCONF, CHOPCONF (with MRES from `p`), IHOLD_IRUN (currents from `p`), TPOWERDOWN,
// TCOOLTHRS and COOLCONF (SGT from `p`) in that order; stops at the first failure.
xy_tmc2130::Result<xy_tmc2130::SpiStatus> configure_driver(xy_tmc2130::Driver& d, const xy_storage::ParameterSet& p);

}  // namespace ap::xy_board
