#pragma once
// One registration function per module; all_obligations() calls them in this order.
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

void add_tmc2130_obligations(ObligationList& out);
void add_axis_obligations(ObligationList& out);     // axis_obligations.cpp
void add_timer_obligations(ObligationList& out);    // timer_obligations.cpp
void add_storage_obligations(ObligationList& out);  // storage_obligations.cpp

// The unit3 profile's obligations (docs/unit3.md), apart from the XY platform's above.
ObligationList unit3_obligations();  // unit3_obligations.cpp

}  // namespace ap::model::smt
