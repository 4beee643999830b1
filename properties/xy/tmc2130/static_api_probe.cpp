// Compiled by the tmc2130_compile.* ctests with one AP_CASE at a time: the static API must
// accept a writable field and refuse, at compile time, an unknown field or a field of a
// read-only register. AP_CASE 0 is the control that must compile, so the failing cases
// fail for the reason they claim, not because the probe is broken.
#include "core/xy/tmc2130/driver.hpp"

namespace chip = ap::xy_tmc2130;

int probe(chip::Driver& d) {
#if AP_CASE == 0
  return d.set<chip::Field::IHOLD_IRUN_IRUN>(12).ok() ? 0 : 1;
#elif AP_CASE == 1
  return d.set<chip::Field::IHOLD_IRUN_IRUNN>(12).ok() ? 0 : 1;
#elif AP_CASE == 2
  return d.set<chip::Field::DRV_STATUS_stst>(1).ok() ? 0 : 1;
#elif AP_CASE == 3
  return chip::field_set<chip::Field::TSTEP_TSTEP>(0u, 1).ok() ? 0 : 1;
#endif
}
