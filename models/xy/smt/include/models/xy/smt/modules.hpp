#pragma once
// The XY profile's proof modules: one registration function per module; xy_obligations()
// calls them in this order.
#include <vector>

#include "models/smt/arith.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

void add_tmc2130_obligations(ObligationList& out);
void add_axis_obligations(ObligationList& out);     // axis_obligations.cpp
void add_timer_obligations(ObligationList& out);    // timer_obligations.cpp
void add_storage_obligations(ObligationList& out);  // storage_obligations.cpp
void add_interp_obligations(ObligationList& out);   // interp_obligations.cpp (docs/interpolation.md)
void add_scurve_obligations(ObligationList& out);   // scurve_obligations.cpp (docs/scurve.md)
// The step terms the interp and scurve obligations are stated over; the conformance tests
// (properties/xy/interp, properties/xy/scurve) evaluate them against the core.
z3::expr interp_axis_step_err(z3::context& c, const z3::expr& n, const z3::expr& a, const z3::expr& err);
z3::expr interp_axis_step_moves(z3::context& c, const z3::expr& n, const z3::expr& a, const z3::expr& err);
std::vector<z3::expr> scurve_step_terms(z3::context& c, const std::vector<z3::expr>& s, const std::vector<z3::expr>& len);

// The XY profile's obligations, in a stable order: the modules above
// (models/xy/smt/src/obligations.cpp).
ObligationList xy_obligations();

}  // namespace ap::model::smt
