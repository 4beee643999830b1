#include "models/xy/smt/modules.hpp"

namespace ap::model::smt {

ObligationList xy_obligations() {
  ObligationList out;
  add_tmc2130_obligations(out);
  add_axis_obligations(out);
  add_timer_obligations(out);
  add_storage_obligations(out);
  add_interp_obligations(out);
  add_scurve_obligations(out);
  return out;
}

}  // namespace ap::model::smt
