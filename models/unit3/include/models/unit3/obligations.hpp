#pragma once
// The unit3 profile's proof obligations (docs/unit3.md), over the shared proof kit.
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

ObligationList unit3_obligations();  // models/unit3/src/obligations.cpp
}  // namespace ap::model::smt
