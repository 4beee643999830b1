#include "core/xy/board/driver_setup.hpp"

#include <bit>

#include "core/xy/tmc2130/fields.hpp"

namespace ap::xy_board {

namespace tmc = ap::xy_tmc2130;

std::int64_t mres_of(std::uint16_t microsteps) { return 8 - std::countr_zero(static_cast<unsigned>(microsteps)); }

tmc::Result<tmc::SpiStatus> configure_driver(tmc::Driver& d, const xy_storage::ParameterSet& p) {
  // GCONF first: en_pwm_mode stays 0 (SpreadCycle) before the chopper is switched on.
  auto r = d.update(tmc::Reg::GCONF, {{tmc::Field::GCONF_diag0_error, kDiag.diag0_error},
                                      {tmc::Field::GCONF_diag0_otpw, kDiag.diag0_otpw},
                                      {tmc::Field::GCONF_diag1_stall, kDiag.diag1_stall}});
  if (!r) return r;
  r = d.update(tmc::Reg::CHOPCONF, {{tmc::Field::CHOPCONF_TOFF, kChopper.toff},
                                    {tmc::Field::CHOPCONF_HSTRT, kChopper.hstrt},
                                    {tmc::Field::CHOPCONF_HEND, kChopper.hend},
                                    {tmc::Field::CHOPCONF_TBL, kChopper.tbl},
                                    {tmc::Field::CHOPCONF_chm, kChopper.chm},
                                    {tmc::Field::CHOPCONF_vsense, kChopper.vsense},
                                    {tmc::Field::CHOPCONF_intpol, kChopper.intpol},
                                    {tmc::Field::CHOPCONF_MRES, mres_of(p.microsteps)}});
  if (!r) return r;
  r = d.update(tmc::Reg::IHOLD_IRUN, {{tmc::Field::IHOLD_IRUN_IHOLD, p.hold_current_cs},
                                      {tmc::Field::IHOLD_IRUN_IRUN, p.run_current_cs},
                                      {tmc::Field::IHOLD_IRUN_IHOLDDELAY, kIholdDelay}});
  if (!r) return r;
  r = d.set(tmc::Field::TPOWERDOWN_TPOWERDOWN, kTpowerdown);
  if (!r) return r;
  r = d.set(tmc::Field::TCOOLTHRS_TCOOLTHRS, kTcoolthrs);
  if (!r) return r;
  return d.set(tmc::Field::COOLCONF_sgt, p.stallguard_threshold);
}

}  // namespace ap::xy_board
