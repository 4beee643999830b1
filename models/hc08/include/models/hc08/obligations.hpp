#pragma once
// The hc08 profile's proof obligations (docs/hc08.md), over the shared proof kit, and its ramp
// and mode B position arithmetic as terms (the conformance test, properties/hc08/proof_test.cpp,
// evaluates them against the core).
#include <vector>

#include <z3++.h>

#include "core/hc08/drive/drive.hpp"
#include "models/smt/arith.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

// The hc08 profile's (docs/hc08.md), and its ramp and mode B position arithmetic as terms (the
// conformance test, properties/hc08/proof_test.cpp, evaluates them against the core).
ObligationList hc08_obligations();  // models/hc08/src/obligations.cpp
z3::expr hc08_ramp_step_term(z3::context& c, const z3::expr& tmod, const z3::expr& target, const z3::expr& stopping,
                             ap::hc08_drive::Drive d);
z3::expr hc08_steps_to_start(z3::context& c, const z3::expr& tmod, ap::hc08_drive::Drive d);
// Mode B's position arithmetic (core/hc08/motor: Motor::start, on_match, set_drive), written
// once over Arith: Sem::Bv is the motor's fields at their C++ widths (int64 as 64-bit
// vectors, remaining_ 32, angle_deg 16), Sem::Int the same text over integers, recording into
// `checks` that every int64 operation's exact result fits (models/hc08/src/obligations.cpp).
struct Hc08ModeBState {
  z3::expr commanded;   // commanded_: 1/360 half step = 1/80 degree
  z3::expr half;        // half_: the rotor, half steps
  z3::expr from_rotor;  // from_rotor_ (Bool)
  z3::expr full;        // seq_.drive() == Drive::Full (Bool)
};
struct Hc08ModeBMove {
  Hc08ModeBState after;  // after start() and every one of its steps (a whole move)
  z3::expr remaining;    // remaining_ after start()
  z3::expr right;        // right_ after start(): the way each of its steps goes (Bool)
  z3::expr steps;        // n, the int64 step count start() computes before clamping it to >= 0
};
// set_drive(full ? Full : Half) at rest.
Hc08ModeBState hc08_set_drive_term(z3::context& c, const Hc08ModeBState& s, const z3::expr& full, Sem sem,
                                   std::vector<Check>* checks);
// start() in mode B with this angle, direction and drive type, then its whole move.
Hc08ModeBMove hc08_mode_b_move_term(z3::context& c, const Hc08ModeBState& before, const z3::expr& angle,
                                    const z3::expr& right, const z3::expr& full, Sem sem,
                                    std::vector<Check>* checks);

}  // namespace ap::model::smt
