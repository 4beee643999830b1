#pragma once
// The TMC2130's register facts as the device model knows them: address, access class, reset
// value and the bits the chip implements, for every register. Written from the Trinamic
// TMC2130 DATASHEET (chapter 5, "Register Map"; section numbers as in Rev. 1.1x, from memory)
// and NOT from the firmware's table (core/xy/tmc2130/regmap.hpp): the model is the oracle the
// firmware is tested against, so a register the firmware misreads must not be misread here
// in the same way. properties/xy/tmc2130/unit_test.cpp (suite tmc2130_datasheet) compares the
// two readings register by register; a disagreement is for a human to settle against the
// datasheet, never to be "fixed" by copying one side into the other.
//
// Cross-checked against Trinamic's TMC-API register definitions (github.com/trinamic/TMC-API,
// now analogdevicesinc/TMC-API: tmc/ic/TMC2130/TMC2130_HW_Abstraction.h field masks,
// TMC2130.h access table and "hardware preset" constants), where noted.
//
// implemented = the union of the fields the datasheet defines in the register; bits outside
// it are reserved: a write does not keep them, a read returns 0 there.
// Header-only, constexpr, no heap.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ap::model::xy_tmc2130::datasheet {

// The datasheet's access column (chapter 5, the register tables' "R/W" column):
//   R   read only;  W  write only (reads return 0: the SPI reply carries no data for it);
//   RW  read and write;  RC  "R+C": read only, every flag cleared by the read.
enum class Access : std::uint8_t { R, W, RW, RC };

constexpr bool readable(Access a) { return a != Access::W; }
constexpr bool writable(Access a) { return a == Access::W || a == Access::RW; }
constexpr bool clears_on_read(Access a) { return a == Access::RC; }
constexpr std::string_view access_name(Access a) {
  switch (a) {
    case Access::R: return "R";
    case Access::W: return "W";
    case Access::RW: return "RW";
    case Access::RC: return "RC";
  }
  return "?";
}

struct RegisterFact {
  std::uint8_t address;       // the 7-bit SPI address
  Access access;
  std::uint32_t reset;        // value after power-up
  std::uint32_t implemented;  // mask of the bits the datasheet defines
  std::string_view name;      // the datasheet's register name
};

// Register addresses (datasheet chapter 5), for the model's own use.
namespace addr {
inline constexpr std::uint8_t GCONF = 0x00, GSTAT = 0x01, IOIN = 0x04;
inline constexpr std::uint8_t IHOLD_IRUN = 0x10, TPOWERDOWN = 0x11, TSTEP = 0x12, TPWMTHRS = 0x13,
                              TCOOLTHRS = 0x14, THIGH = 0x15;
inline constexpr std::uint8_t XDIRECT = 0x2D, VDCMIN = 0x33;
inline constexpr std::uint8_t MSLUT0 = 0x60, MSLUTSEL = 0x68, MSLUTSTART = 0x69, MSCNT = 0x6A, MSCURACT = 0x6B;
inline constexpr std::uint8_t CHOPCONF = 0x6C, COOLCONF = 0x6D, DCCTRL = 0x6E, DRV_STATUS = 0x6F,
                              PWMCONF = 0x70, PWM_SCALE = 0x71, ENCM_CTRL = 0x72, LOST_STEPS = 0x73;
}  // namespace addr

inline constexpr std::array<RegisterFact, 31> kRegisters{{
    // ---- 5.1 General Configuration Registers (0x00..0x0F) ----
    // GCONF: I_scale_analog 0, internal_Rsense 1, en_pwm_mode 2, enc_commutation 3, shaft 4,
    // diag0_error 5, diag0_otpw 6, diag0_stall 7, diag1_stall 8, diag1_index 9,
    // diag1_onstate 10, diag1_steps_skipped 11, diag0_int_pushpull 12, diag1_pushpull 13,
    // small_hysteresis 14, stop_enable 15, direct_mode 16, test_mode 17 (TMC-API: bits 0..17).
    // No reset defaults: the TMC2130 has no OTP, every flag powers up 0.
    {0x00, Access::RW, 0x00000000U, 0x0003FFFFU, "GCONF"},
    // GSTAT (R+C): reset 0, drv_err 1, uv_cp 2. reset: "Indicates that the IC has been reset
    // since the last read access to GSTAT" -> set after power-up.
    {0x01, Access::RC, 0x00000001U, 0x00000007U, "GSTAT"},
    // IOIN (R): STEP 0, DIR 1, DCEN_CFG4 2, DCIN_CFG5 3, DRV_ENN_CFG6 4, DCO 5, bit 6 "always 1",
    // bit 7 don't care (not counted); VERSION 31..24 = 0x11 ("first version of the IC").
    // Reset = what a read returns with all input pins low: VERSION and bit 6.
    // (bit 6/7 wording from memory; TMC-API defines only bits 0..5 and VERSION.)
    {0x04, Access::R, 0x11000040U, 0xFF00007FU, "IOIN"},

    // ---- 5.2 Velocity Dependent Driver Feature Control Register Set (0x10..0x1F) ----
    // IHOLD_IRUN: IHOLD 4..0, IRUN 12..8, IHOLDDELAY 19..16.
    {0x10, Access::W, 0x00000000U, 0x000F1F1FU, "IHOLD_IRUN"},
    // TPOWERDOWN: 7..0 (0..255, x 2^18 clocks). No reset default in the TMC2130 datasheet (the
    // value 10 is the Getting Started example; later chips (TMC5160/2160) state "Reset default
    // = 10", from memory).
    {0x11, Access::W, 0x00000000U, 0x000000FFU, "TPOWERDOWN"},
    // TSTEP (R): 19..0, the measured time between two 1/256 microsteps; "(2^20)-1 in case of
    // overflow or stand still" -> after power-up, with no STEP edge yet, it reads 0xFFFFF.
    {0x12, Access::R, 0x000FFFFFU, 0x000FFFFFU, "TSTEP"},
    // TPWMTHRS, TCOOLTHRS, THIGH: 19..0 each.
    {0x13, Access::W, 0x00000000U, 0x000FFFFFU, "TPWMTHRS"},
    {0x14, Access::W, 0x00000000U, 0x000FFFFFU, "TCOOLTHRS"},
    {0x15, Access::W, 0x00000000U, 0x000FFFFFU, "THIGH"},

    // ---- 5.3 SPI Mode Register ----
    // XDIRECT (RW): coil A current 8..0 (signed 9 bit), coil B current 24..16 (signed 9 bit).
    {0x2D, Access::RW, 0x00000000U, 0x01FF01FFU, "XDIRECT"},

    // ---- 5.4 dcStep Minimum Velocity Register ----
    // VDCMIN: 22..0 (23 bits, from memory; TMC-API's mask is 0x07FFFFFF, 27 bits).
    {0x33, Access::W, 0x00000000U, 0x007FFFFFU, "VDCMIN"},

    // ---- 5.5 Motor Driver Registers (0x60..0x7F), microstep table (5.5.1) ----
    // MSLUT[0..7]: 32 bits each; the power-up defaults are the datasheet's default sine wave
    // table (same values as TMC-API's "hardware preset" constants for 0x60..0x67).
    {0x60, Access::W, 0xAAAAB554U, 0xFFFFFFFFU, "MSLUT0"},
    {0x61, Access::W, 0x4A9554AAU, 0xFFFFFFFFU, "MSLUT1"},
    {0x62, Access::W, 0x24492929U, 0xFFFFFFFFU, "MSLUT2"},
    {0x63, Access::W, 0x10104222U, 0xFFFFFFFFU, "MSLUT3"},
    {0x64, Access::W, 0xFBFFFFFFU, 0xFFFFFFFFU, "MSLUT4"},
    {0x65, Access::W, 0xB5BB777DU, 0xFFFFFFFFU, "MSLUT5"},
    {0x66, Access::W, 0x49295556U, 0xFFFFFFFFU, "MSLUT6"},
    {0x67, Access::W, 0x00404222U, 0xFFFFFFFFU, "MSLUT7"},
    // MSLUTSEL: W0 1..0, W1 3..2, W2 5..4, W3 7..6, X1 15..8, X2 23..16, X3 31..24.
    // Default W0=2, W1=W2=W3=1, X1=128, X2=X3=255.
    {0x68, Access::W, 0xFFFF8056U, 0xFFFFFFFFU, "MSLUTSEL"},
    // MSLUTSTART: START_SIN 7..0, START_SIN90 23..16. Default START_SIN=0, START_SIN90=247.
    {0x69, Access::W, 0x00F70000U, 0x00FF00FFU, "MSLUTSTART"},
    // MSCNT (R): 9..0, the microstep counter.
    {0x6A, Access::R, 0x00000000U, 0x000003FFU, "MSCNT"},
    // MSCURACT (R): CUR_A 8..0, CUR_B 24..16 (signed 9 bit). No power-up value is stated; it is
    // the current the default sine table gives at MSCNT = 0 (5.5 MSLUTSTART: START_SIN 0,
    // START_SIN90 247), so CUR_A 0, CUR_B 247 (derived from the table's defaults).
    {0x6B, Access::R, 0x00F70000U, 0x01FF01FFU, "MSCURACT"},

    // ---- 5.5 Motor Driver Registers, driver register set (0x6C..0x7F) ----
    // CHOPCONF (RW): TOFF 3..0, HSTRT/TFD[2..0] 6..4, HEND/OFFSET 10..7, fd3 11, disfdcc 12,
    // rndtf 13, chm 14, TBL 16..15, vsense 17, vhighfs 18, vhighchm 19, sync 23..20,
    // MRES 27..24, intpol 28, dedge 29, diss2g 30; bit 31 reserved. Powers up 0 (TOFF=0:
    // driver off).
    {0x6C, Access::RW, 0x00000000U, 0x7FFFFFFFU, "CHOPCONF"},
    // COOLCONF (W): semin 3..0, seup 6..5, semax 11..8, sedn 14..13, seimin 15,
    // sgt 22..16 (signed 7 bit), sfilt 24.
    {0x6D, Access::W, 0x00000000U, 0x017FEF6FU, "COOLCONF"},
    // DCCTRL (W): DC_TIME 9..0, DC_SG 23..16.
    {0x6E, Access::W, 0x00000000U, 0x00FF03FFU, "DCCTRL"},
    // DRV_STATUS (R): SG_RESULT 9..0, fsactive 15, CS_ACTUAL 20..16, stallGuard 24, ot 25,
    // otpw 26, s2ga 27, s2gb 28, ola 29, olb 30, stst 31. At power-up the motor stands
    // still: stst set.
    {0x6F, Access::R, 0x80000000U, 0xFF1F83FFU, "DRV_STATUS"},
    // PWMCONF (W): PWM_AMPL 7..0, PWM_GRAD 15..8, pwm_freq 17..16, pwm_autoscale 18,
    // pwm_symmetric 19, freewheel 21..20. Reset default 0x00050480 (PWM_AMPL=128,
    // PWM_GRAD=4, pwm_freq=%01), as the datasheet's PWMCONF table states.
    {0x70, Access::W, 0x00050480U, 0x003FFFFFU, "PWMCONF"},
    // PWM_SCALE (R): 7..0.
    {0x71, Access::R, 0x00000000U, 0x000000FFU, "PWM_SCALE"},
    // ENCM_CTRL (W): inv 0, maxspeed 1.
    {0x72, Access::W, 0x00000000U, 0x00000003U, "ENCM_CTRL"},
    // LOST_STEPS (R): 19..0.
    {0x73, Access::R, 0x00000000U, 0x000FFFFFU, "LOST_STEPS"},
}};

// The fact for a 7-bit address; nullptr for an address the datasheet leaves unused.
constexpr const RegisterFact* fact(std::uint8_t address) {
  for (const auto& r : kRegisters) {
    if (r.address == address) return &r;
  }
  return nullptr;
}

// Self-consistency of the table (not a check against the firmware).
namespace detail {
constexpr bool well_formed() {
  for (std::size_t i = 0; i < kRegisters.size(); ++i) {
    const auto& r = kRegisters[i];
    if (r.address > 0x7F) return false;
    if ((r.reset & ~r.implemented) != 0) return false;  // a reset bit the chip does not have
    if (r.name.empty()) return false;
    if (i > 0 && kRegisters[i - 1].address >= r.address) return false;  // ascending, unique
  }
  return true;
}
// Written as functions: gcc's -Waddress rejects comparing a constant element pointer with null
// inside a static_assert.
constexpr bool chopconf_is_rw() {
  const RegisterFact* f = fact(addr::CHOPCONF);
  return f != nullptr && f->access == Access::RW;
}
constexpr bool unused_address_is_absent() {
  const RegisterFact* f = fact(0x05);
  return f == nullptr;
}
}  // namespace detail
static_assert(detail::well_formed(), "datasheet table: addresses ascending, reset within implemented bits");
static_assert(detail::chopconf_is_rw());
static_assert(detail::unused_address_is_absent());

}  // namespace ap::model::xy_tmc2130::datasheet
