#pragma once
// One registration function per module; all_obligations() calls them in this order.
#include "models/smt/obligation.hpp"

namespace ap::smt {

void add_tmc2130_obligations(ObligationList& out);

}  // namespace ap::smt
