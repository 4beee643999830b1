#pragma once
// The TMC2130 register map (datasheet rev. 1.15, section 5): the only place where addresses,
// access modes, reset values and field layouts are written down. Everything else (driver,
// device model, Z3 obligations, `axisproof regs`, docs/tmc2130.md) is derived from these
// two lists, so a wrong mask can only be wrong once, and the proofs see that very mask.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace ap::xy_tmc2130 {

enum class Access : std::uint8_t {
  R,   // read-only status
  W,   // write-only: reads return nothing useful, so the driver keeps a shadow
  RW,  // readable and writable: written values are verified by reading back
  RC,  // read-only, flags clear when read (GSTAT)
};

// X(name, address, access, reset value). Reset values are the chip's power-on contents;
// all registers reset to 0 except the microstep table (MSLUT*) and PWMCONF.
#define AP_TMC2130_REGISTERS(X)               \
  X(GCONF, 0x00, RW, 0x00000000u)             \
  X(GSTAT, 0x01, RC, 0x00000001u)             \
  X(IOIN, 0x04, R, 0x11000040u)               \
  X(IHOLD_IRUN, 0x10, W, 0x00000000u)         \
  X(TPOWERDOWN, 0x11, W, 0x00000000u)         \
  X(TSTEP, 0x12, R, 0x000FFFFFu)              \
  X(TPWMTHRS, 0x13, W, 0x00000000u)           \
  X(TCOOLTHRS, 0x14, W, 0x00000000u)          \
  X(THIGH, 0x15, W, 0x00000000u)              \
  X(XDIRECT, 0x2D, RW, 0x00000000u)           \
  X(VDCMIN, 0x33, W, 0x00000000u)             \
  X(MSLUT0, 0x60, W, 0xAAAAB554u)             \
  X(MSLUT1, 0x61, W, 0x4A9554AAu)             \
  X(MSLUT2, 0x62, W, 0x24492929u)             \
  X(MSLUT3, 0x63, W, 0x10104222u)             \
  X(MSLUT4, 0x64, W, 0xFBFFFFFFu)             \
  X(MSLUT5, 0x65, W, 0xB5BB777Du)             \
  X(MSLUT6, 0x66, W, 0x49295556u)             \
  X(MSLUT7, 0x67, W, 0x00404222u)             \
  X(MSLUTSEL, 0x68, W, 0xFFFF8056u)           \
  X(MSLUTSTART, 0x69, W, 0x00F70000u)         \
  X(MSCNT, 0x6A, R, 0x00000000u)              \
  X(MSCURACT, 0x6B, R, 0x00F70000u)           \
  X(CHOPCONF, 0x6C, RW, 0x00000000u)          \
  X(COOLCONF, 0x6D, W, 0x00000000u)           \
  X(DCCTRL, 0x6E, W, 0x00000000u)             \
  X(DRV_STATUS, 0x6F, R, 0x80000000u)         \
  X(PWMCONF, 0x70, W, 0x00050480u)            \
  X(PWM_SCALE, 0x71, R, 0x00000000u)          \
  X(ENCM_CTRL, 0x72, W, 0x00000000u)          \
  X(LOST_STEPS, 0x73, R, 0x00000000u)

// X(register, field, lsb, width, signed, min, max). min/max are the values the datasheet
// allows, which can be narrower than the width (MRES 0..8, XDIRECT coil currents ±255).
// Signed fields are two's complement inside their width.
#define AP_TMC2130_FIELDS(X)                                      \
  X(GCONF, I_scale_analog, 0, 1, false, 0, 1)                     \
  X(GCONF, internal_Rsense, 1, 1, false, 0, 1)                    \
  X(GCONF, en_pwm_mode, 2, 1, false, 0, 1)                        \
  X(GCONF, enc_commutation, 3, 1, false, 0, 1)                    \
  X(GCONF, shaft, 4, 1, false, 0, 1)                              \
  X(GCONF, diag0_error, 5, 1, false, 0, 1)                        \
  X(GCONF, diag0_otpw, 6, 1, false, 0, 1)                         \
  X(GCONF, diag0_stall, 7, 1, false, 0, 1)                        \
  X(GCONF, diag1_stall, 8, 1, false, 0, 1)                        \
  X(GCONF, diag1_index, 9, 1, false, 0, 1)                        \
  X(GCONF, diag1_onstate, 10, 1, false, 0, 1)                     \
  X(GCONF, diag1_steps_skipped, 11, 1, false, 0, 1)               \
  X(GCONF, diag0_int_pushpull, 12, 1, false, 0, 1)                \
  X(GCONF, diag1_pushpull, 13, 1, false, 0, 1)                    \
  X(GCONF, small_hysteresis, 14, 1, false, 0, 1)                  \
  X(GCONF, stop_enable, 15, 1, false, 0, 1)                       \
  X(GCONF, direct_mode, 16, 1, false, 0, 1)                       \
  X(GCONF, test_mode, 17, 1, false, 0, 1)                         \
  X(GSTAT, reset, 0, 1, false, 0, 1)                              \
  X(GSTAT, drv_err, 1, 1, false, 0, 1)                            \
  X(GSTAT, uv_cp, 2, 1, false, 0, 1)                              \
  X(IOIN, STEP, 0, 1, false, 0, 1)                                \
  X(IOIN, DIR, 1, 1, false, 0, 1)                                 \
  X(IOIN, DCEN_CFG4, 2, 1, false, 0, 1)                           \
  X(IOIN, DCIN_CFG5, 3, 1, false, 0, 1)                           \
  X(IOIN, DRV_ENN_CFG6, 4, 1, false, 0, 1)                        \
  X(IOIN, DCO, 5, 1, false, 0, 1)                                 \
  X(IOIN, always_1, 6, 1, false, 0, 1)                            \
  X(IOIN, VERSION, 24, 8, false, 0, 255)                          \
  X(IHOLD_IRUN, IHOLD, 0, 5, false, 0, 31)                        \
  X(IHOLD_IRUN, IRUN, 8, 5, false, 0, 31)                         \
  X(IHOLD_IRUN, IHOLDDELAY, 16, 4, false, 0, 15)                  \
  X(TPOWERDOWN, TPOWERDOWN, 0, 8, false, 0, 255)                  \
  X(TSTEP, TSTEP, 0, 20, false, 0, 1048575)                       \
  X(TPWMTHRS, TPWMTHRS, 0, 20, false, 0, 1048575)                 \
  X(TCOOLTHRS, TCOOLTHRS, 0, 20, false, 0, 1048575)               \
  X(THIGH, THIGH, 0, 20, false, 0, 1048575)                       \
  X(XDIRECT, COIL_A, 0, 9, true, -255, 255)                       \
  X(XDIRECT, COIL_B, 16, 9, true, -255, 255)                      \
  X(VDCMIN, VDCMIN, 0, 23, false, 0, 8388607)                     \
  X(MSLUT0, MSLUT0, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT1, MSLUT1, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT2, MSLUT2, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT3, MSLUT3, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT4, MSLUT4, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT5, MSLUT5, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT6, MSLUT6, 0, 32, false, 0, 4294967295)                  \
  X(MSLUT7, MSLUT7, 0, 32, false, 0, 4294967295)                  \
  X(MSLUTSEL, W0, 0, 2, false, 0, 3)                              \
  X(MSLUTSEL, W1, 2, 2, false, 0, 3)                              \
  X(MSLUTSEL, W2, 4, 2, false, 0, 3)                              \
  X(MSLUTSEL, W3, 6, 2, false, 0, 3)                              \
  X(MSLUTSEL, X1, 8, 8, false, 0, 255)                            \
  X(MSLUTSEL, X2, 16, 8, false, 0, 255)                           \
  X(MSLUTSEL, X3, 24, 8, false, 0, 255)                           \
  X(MSLUTSTART, START_SIN, 0, 8, false, 0, 255)                   \
  X(MSLUTSTART, START_SIN90, 16, 8, false, 0, 255)                \
  X(MSCNT, MSCNT, 0, 10, false, 0, 1023)                          \
  X(MSCURACT, CUR_A, 0, 9, true, -255, 255)                       \
  X(MSCURACT, CUR_B, 16, 9, true, -255, 255)                      \
  X(CHOPCONF, TOFF, 0, 4, false, 0, 15)                           \
  X(CHOPCONF, HSTRT, 4, 3, false, 0, 7)                           \
  X(CHOPCONF, HEND, 7, 4, false, 0, 15)                           \
  X(CHOPCONF, fd3, 11, 1, false, 0, 1)                            \
  X(CHOPCONF, disfdcc, 12, 1, false, 0, 1)                        \
  X(CHOPCONF, rndtf, 13, 1, false, 0, 1)                          \
  X(CHOPCONF, chm, 14, 1, false, 0, 1)                            \
  X(CHOPCONF, TBL, 15, 2, false, 0, 3)                            \
  X(CHOPCONF, vsense, 17, 1, false, 0, 1)                         \
  X(CHOPCONF, vhighfs, 18, 1, false, 0, 1)                        \
  X(CHOPCONF, vhighchm, 19, 1, false, 0, 1)                       \
  X(CHOPCONF, sync, 20, 4, false, 0, 15)                          \
  X(CHOPCONF, MRES, 24, 4, false, 0, 8)                           \
  X(CHOPCONF, intpol, 28, 1, false, 0, 1)                         \
  X(CHOPCONF, dedge, 29, 1, false, 0, 1)                          \
  X(CHOPCONF, diss2g, 30, 1, false, 0, 1)                         \
  X(COOLCONF, semin, 0, 4, false, 0, 15)                          \
  X(COOLCONF, seup, 5, 2, false, 0, 3)                            \
  X(COOLCONF, semax, 8, 4, false, 0, 15)                          \
  X(COOLCONF, sedn, 13, 2, false, 0, 3)                           \
  X(COOLCONF, seimin, 15, 1, false, 0, 1)                         \
  X(COOLCONF, sgt, 16, 7, true, -64, 63)                          \
  X(COOLCONF, sfilt, 24, 1, false, 0, 1)                          \
  X(DCCTRL, DC_TIME, 0, 10, false, 0, 1023)                       \
  X(DCCTRL, DC_SG, 16, 8, false, 0, 255)                          \
  X(DRV_STATUS, SG_RESULT, 0, 10, false, 0, 1023)                 \
  X(DRV_STATUS, fsactive, 15, 1, false, 0, 1)                     \
  X(DRV_STATUS, CS_ACTUAL, 16, 5, false, 0, 31)                   \
  X(DRV_STATUS, stallGuard, 24, 1, false, 0, 1)                   \
  X(DRV_STATUS, ot, 25, 1, false, 0, 1)                           \
  X(DRV_STATUS, otpw, 26, 1, false, 0, 1)                         \
  X(DRV_STATUS, s2ga, 27, 1, false, 0, 1)                         \
  X(DRV_STATUS, s2gb, 28, 1, false, 0, 1)                         \
  X(DRV_STATUS, ola, 29, 1, false, 0, 1)                          \
  X(DRV_STATUS, olb, 30, 1, false, 0, 1)                          \
  X(DRV_STATUS, stst, 31, 1, false, 0, 1)                         \
  X(PWMCONF, PWM_AMPL, 0, 8, false, 0, 255)                       \
  X(PWMCONF, PWM_GRAD, 8, 8, false, 0, 255)                       \
  X(PWMCONF, pwm_freq, 16, 2, false, 0, 3)                        \
  X(PWMCONF, pwm_autoscale, 18, 1, false, 0, 1)                   \
  X(PWMCONF, pwm_symmetric, 19, 1, false, 0, 1)                   \
  X(PWMCONF, freewheel, 20, 2, false, 0, 3)                       \
  X(PWM_SCALE, PWM_SCALE, 0, 8, false, 0, 255)                    \
  X(ENCM_CTRL, inv, 0, 1, false, 0, 1)                            \
  X(ENCM_CTRL, maxspeed, 1, 1, false, 0, 1)                       \
  X(LOST_STEPS, LOST_STEPS, 0, 20, false, 0, 1048575)

// Register enumerators carry the SPI address, so `Reg::IHOLD_IRUN` is 0x10 on the wire.
enum class Reg : std::uint8_t {
#define AP_X(name, addr, access, reset) name = (addr),
  AP_TMC2130_REGISTERS(AP_X)
#undef AP_X
};

// Field enumerators are dense indices into kFields; a misspelt field does not compile.
enum class Field : std::uint8_t {
#define AP_X(reg, name, lsb, width, is_signed, lo, hi) reg##_##name,
  AP_TMC2130_FIELDS(AP_X)
#undef AP_X
};

struct RegisterInfo {
  std::string_view name;
  Reg reg;
  Access access;
  std::uint32_t reset;
  std::uint8_t first_field;  // index into kFields; a register's fields are contiguous there
  std::uint8_t field_count;
};

struct FieldInfo {
  std::string_view name;
  Field field;
  Reg reg;
  std::uint32_t mask;
  std::uint8_t shift;
  std::uint8_t width;
  bool is_signed;
  std::int64_t min;  // int64 holds both the 32-bit MSLUT words and the signed fields
  std::int64_t max;
};

namespace detail {
constexpr std::uint32_t mask_of(unsigned lsb, unsigned width) {
  // width 32 is legal (MSLUT), and 1u << 32 is undefined, hence the split.
  const std::uint32_t low = width >= 32u ? 0xFFFFFFFFu : ((std::uint32_t{1} << width) - 1u);
  return static_cast<std::uint32_t>(low << lsb);
}
}  // namespace detail

// The section attribute keeps this table in flash on the Cortex-M4: arm-none-eabi-gcc 12 puts
// an `inline constexpr` object that holds pointers into .data (RAM) otherwise. The same below.
[[gnu::section(".rodata.ap.tmc2130.fields")]] inline constexpr std::array kFields{
#define AP_X(reg, name, lsb, width, is_signed, lo, hi)                                     \
  FieldInfo{#name, Field::reg##_##name, Reg::reg, detail::mask_of(lsb, width), lsb, width, \
            is_signed, static_cast<std::int64_t>(lo##LL), static_cast<std::int64_t>(hi##LL)},
    AP_TMC2130_FIELDS(AP_X)
#undef AP_X
};

namespace detail {
constexpr std::uint8_t first_field_of(Reg r) {
  for (std::size_t i = 0; i < kFields.size(); ++i) {
    if (kFields[i].reg == r) return static_cast<std::uint8_t>(i);
  }
  return 0xFF;
}
constexpr std::uint8_t field_count_of(Reg r) {
  std::uint8_t n = 0;
  for (const auto& f : kFields) n = static_cast<std::uint8_t>(n + (f.reg == r ? 1 : 0));
  return n;
}
}  // namespace detail

[[gnu::section(".rodata.ap.tmc2130.registers")]] inline constexpr std::array kRegisters{
#define AP_X(name, addr, access, reset)                                                     \
  RegisterInfo{#name, Reg::name, Access::access, reset, detail::first_field_of(Reg::name), \
               detail::field_count_of(Reg::name)},
    AP_TMC2130_REGISTERS(AP_X)
#undef AP_X
};

inline constexpr std::size_t kRegisterCount = kRegisters.size();
inline constexpr std::size_t kFieldCount = kFields.size();

constexpr std::uint8_t address(Reg r) { return static_cast<std::uint8_t>(r); }

// Dense index 0..kRegisterCount-1 of a register, for shadow arrays.
constexpr std::optional<std::size_t> register_index(std::uint8_t addr) {
  for (std::size_t i = 0; i < kRegisters.size(); ++i) {
    if (address(kRegisters[i].reg) == addr) return i;
  }
  return std::nullopt;
}
constexpr std::size_t index_of(Reg r) { return *register_index(address(r)); }

constexpr const RegisterInfo& info(Reg r) { return kRegisters[index_of(r)]; }
constexpr const FieldInfo& info(Field f) { return kFields[static_cast<std::size_t>(f)]; }

constexpr bool readable(Access a) { return a != Access::W; }
constexpr bool writable(Access a) { return a == Access::W || a == Access::RW; }
constexpr bool readable(Reg r) { return readable(info(r).access); }
constexpr bool writable(Reg r) { return writable(info(r).access); }

constexpr std::string_view access_name(Access a) {
  switch (a) {
    case Access::R: return "R";
    case Access::W: return "W";
    case Access::RW: return "RW";
    case Access::RC: return "RC";
  }
  return "?";
}

// Bits the chip implements in a register; others read back as 0.
constexpr std::uint32_t implemented_mask(Reg r) {
  std::uint32_t m = 0;
  const auto& ri = info(r);
  for (std::size_t i = ri.first_field; i < std::size_t{ri.first_field} + ri.field_count; ++i) {
    m |= kFields[i].mask;
  }
  return m;
}

constexpr std::optional<Reg> find_register(std::string_view name) {
  for (const auto& r : kRegisters) {
    if (r.name == name) return r.reg;
  }
  return std::nullopt;
}
constexpr std::optional<Reg> find_register(std::uint8_t addr) {
  if (auto i = register_index(addr)) return kRegisters[*i].reg;
  return std::nullopt;
}
// Field names repeat across registers only by accident, so lookup is by register and name.
constexpr std::optional<Field> find_field(Reg r, std::string_view name) {
  const auto& ri = info(r);
  for (std::size_t i = ri.first_field; i < std::size_t{ri.first_field} + ri.field_count; ++i) {
    if (kFields[i].name == name) return kFields[i].field;
  }
  return std::nullopt;
}

namespace detail {
constexpr bool table_is_consistent() {
  for (std::size_t i = 0; i < kFields.size(); ++i) {
    const auto& f = kFields[i];
    if (static_cast<std::size_t>(f.field) != i) return false;
    if (f.width == 0 || f.width > 32 || f.shift + f.width > 32) return false;
    if (f.min > f.max) return false;
    const std::int64_t span = std::int64_t{1} << f.width;
    if (f.is_signed ? (f.min < -span / 2 || f.max > span / 2 - 1) : (f.min < 0 || f.max > span - 1)) {
      return false;
    }
    for (std::size_t j = i + 1; j < kFields.size(); ++j) {
      if (kFields[j].reg == f.reg && (kFields[j].mask & f.mask) != 0) return false;
    }
  }
  for (std::size_t i = 0; i < kRegisters.size(); ++i) {
    const auto& r = kRegisters[i];
    if (r.field_count == 0) return false;
    if (i > 0 && address(kRegisters[i - 1].reg) >= address(r.reg)) return false;
    if (address(r.reg) > 0x7F) return false;
    // Fields of one register must be adjacent in kFields, so [first, first+count) is exact.
    for (std::size_t k = r.first_field; k < std::size_t{r.first_field} + r.field_count; ++k) {
      if (kFields[k].reg != r.reg) return false;
    }
    if ((r.reset & ~implemented_mask(r.reg)) != 0 && r.access != Access::R) return false;
  }
  return true;
}
}  // namespace detail

// Build-time guard: overlapping masks, widths past bit 31, ranges wider than the width or
// unsorted addresses stop compilation. The Z3 obligations prove the arithmetic on top.
static_assert(detail::table_is_consistent(), "TMC2130 register table is inconsistent");

}  // namespace ap::xy_tmc2130
