#pragma once
// One registration function per module; all_obligations() calls them in this order.
#include <vector>

#include "core/hc08_drive/drive.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

void add_tmc2130_obligations(ObligationList& out);
void add_axis_obligations(ObligationList& out);     // axis_obligations.cpp
void add_timer_obligations(ObligationList& out);    // timer_obligations.cpp
void add_storage_obligations(ObligationList& out);  // storage_obligations.cpp
void add_interp_obligations(ObligationList& out);   // interp_obligations.cpp (docs/interpolation.md)
void add_scurve_obligations(ObligationList& out);   // scurve_obligations.cpp (docs/scurve.md)
// The step terms the interp and scurve obligations are stated over; the conformance tests
// (properties/interp, properties/scurve) evaluate them against the core.
z3::expr interp_axis_step_err(z3::context& c, const z3::expr& n, const z3::expr& a, const z3::expr& err);
z3::expr interp_axis_step_moves(z3::context& c, const z3::expr& n, const z3::expr& a, const z3::expr& err);
std::vector<z3::expr> scurve_step_terms(z3::context& c, const std::vector<z3::expr>& s, const std::vector<z3::expr>& len);

// The unit3 profile's obligations (docs/unit3.md), apart from the XY platform's above.
ObligationList unit3_obligations();  // unit3_obligations.cpp
// The hc08 profile's (docs/hc08.md), and its ramp arithmetic as terms (the conformance test
// evaluates them against the core).
ObligationList hc08_obligations();  // hc08_obligations.cpp
z3::expr hc08_ramp_step_term(z3::context& c, const z3::expr& tmod, const z3::expr& target, const z3::expr& stopping,
                             ap::hc08_drive::Drive d);
z3::expr hc08_steps_to_start(z3::context& c, const z3::expr& tmod, ap::hc08_drive::Drive d);

}  // namespace ap::model::smt
