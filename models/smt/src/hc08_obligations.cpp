// The HC08 unit's obligations (docs/hc08.md "Ramp", "Mode B"), over the core's constants
// (core/hc08_timer: start frequencies, kAccelStep, tmod_at_hz). The ramp's arithmetic is
// stated here as the core writes it (ramp_step, steps_to_start, the mode B choice of
// Motor::on_match); hc08_ramp_step_term() is also what the conformance test
// (properties/hc08/proof_test.cpp) evaluates against the core on concrete values.
#include <cstdint>
#include <string>

#include "core/hc08_drive/drive.hpp"
#include "core/hc08_timer/timer.hpp"
#include "models/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {

namespace t = ap::hc08_timer;
using ap::hc08_drive::Drive;

z3::expr hc08_steps_to_start(z3::context& c, const z3::expr& tmod, Drive d) {
  const z3::expr start = c.bv_val(t::tmod_at_hz(t::start_hz(d)), 32);
  return z3::ite(z3::uge(tmod, start), c.bv_val(0, 32), z3::udiv(start - tmod + c.bv_val(t::kAccelStep - 1U, 32), c.bv_val(t::kAccelStep, 32)));
}

z3::expr hc08_ramp_step_term(z3::context& c, const z3::expr& tmod, const z3::expr& target, const z3::expr& stopping, Drive d) {
  const z3::expr start = c.bv_val(t::tmod_at_hz(t::start_hz(d)), 32);
  const z3::expr step = c.bv_val(t::kAccelStep, 32);
  const z3::expr goal = z3::ite(stopping, start, target);
  return z3::ite(z3::ugt(tmod, goal), z3::ite(z3::ugt(tmod - goal, step), tmod - step, goal),
                 z3::ite(z3::ult(tmod, goal), z3::ite(z3::ugt(goal - tmod, step), tmod + step, goal), tmod));
}

namespace {

// Mode B after a step, with `left` steps still to go (>= 1) and the period `now` the step just
// used (at PS 0, at most the start period): the period the motor programs next.
z3::expr mode_b_next(z3::context& c, const z3::expr& now, const z3::expr& target, const z3::expr& left, Drive d) {
  const z3::expr one = c.bv_val(1, 32);
  const z3::expr up = hc08_ramp_step_term(c, now, target, c.bool_val(false), d);
  const z3::expr down = hc08_ramp_step_term(c, now, target, c.bool_val(true), d);
  const auto keeps = [&](const z3::expr& p) { return z3::uge(left, one + hc08_steps_to_start(c, p, d)); };
  return z3::ite(keeps(up), up, z3::ite(keeps(now), now, down));
}

void add_mode_b_ramp(ObligationList& out, Drive d) {
  const std::string name = std::string("hc08.ramp.mode_b_ends_at_start.") + (d == Drive::Full ? "full" : "half");
  out.push_back({name,
                 "QF_BV 32-bit, by induction over steps, for every period between the set speed and the start "
                 "frequency and every count still to go: if the count covers the ramp back (left >= "
                 "steps_to_start(now)), the period the motor programs next keeps it one step ahead "
                 "(left >= 1 + steps_to_start(next)), moves by at most kAccelStep and is never faster than the set "
                 "speed; so a mode B move's last step is at or below the start frequency",
                 [d](unsigned ms) {
                   z3::context& c = shared_context();
                   const z3::expr now = c.bv_const("now", 32);
                   const z3::expr target = c.bv_const("target", 32);
                   const z3::expr left = c.bv_const("left", 32);
                   const z3::expr start = c.bv_val(t::tmod_at_hz(t::start_hz(d)), 32);
                   const z3::expr fastest = c.bv_val(t::tmod_at_hz(t::max_hz(d)), 32);
                   const z3::expr pre = z3::uge(target, fastest) && z3::ult(target, start) && z3::uge(now, target) &&
                                        z3::ule(now, start) && z3::uge(left, c.bv_val(1, 32)) &&
                                        z3::ule(left, c.bv_val(1U << 20, 32)) && z3::uge(left, hc08_steps_to_start(c, now, d));
                   const z3::expr next = mode_b_next(c, now, target, left, d);
                   const z3::expr step = c.bv_val(t::kAccelStep, 32);
                   const z3::expr claim = z3::implies(
                       pre, z3::uge(left, c.bv_val(1, 32) + hc08_steps_to_start(c, next, d)) && z3::uge(next, target) &&
                                z3::ule(next, start) && z3::ule(z3::ite(z3::uge(next, now), next - now, now - next), step));
                   return check_valid(c, claim, ms, {{"now", now}, {"target", target}, {"left", left}, {"next", next}});
                 }});
}

void add_stop(ObligationList& out, Drive d) {
  const std::string name = std::string("hc08.ramp.stop_decelerates.") + (d == Drive::Full ? "full" : "half");
  out.push_back({name,
                 "QF_BV 32-bit: once stopping (mode A's SET, or a reversal), every step's period grows by kAccelStep "
                 "until the start period and never shrinks, so the motor stops or reverses only at or below the start "
                 "frequency, within ceil((start - now) / kAccelStep) steps",
                 [d](unsigned ms) {
                   z3::context& c = shared_context();
                   const z3::expr now = c.bv_const("now", 32);
                   const z3::expr target = c.bv_const("target", 32);
                   const z3::expr start = c.bv_val(t::tmod_at_hz(t::start_hz(d)), 32);
                   const z3::expr fastest = c.bv_val(t::tmod_at_hz(t::max_hz(d)), 32);
                   const z3::expr pre = z3::uge(target, fastest) && z3::ule(target, start) && z3::uge(now, fastest) && z3::ult(now, start);
                   const z3::expr next = hc08_ramp_step_term(c, now, target, c.bool_val(true), d);
                   const z3::expr claim = z3::implies(
                       pre, z3::ugt(next, now) && z3::ule(next, start) &&
                                hc08_steps_to_start(c, next, d) + c.bv_val(1, 32) == hc08_steps_to_start(c, now, d));
                   return check_valid(c, claim, ms, {{"now", now}, {"target", target}, {"next", next}});
                 }});
}

}  // namespace

ObligationList hc08_obligations() {
  ObligationList out;
  add_mode_b_ramp(out, Drive::Full);
  add_mode_b_ramp(out, Drive::Half);
  add_stop(out, Drive::Full);
  add_stop(out, Drive::Half);
  out.push_back({"hc08.mode_b.no_drift",
                 "QF_BV 24-bit (|C' - 360 s| < 360 + 9999 * 80 < 2^23), by induction over moves: with the commanded position C (1/360 step) less than a step "
                 "from the rotor's 360 s (g = C - 360 s, |g| < 360), a move of any angle 0..9999 degrees in either "
                 "direction, 40 or 80 steps per turn, rounded to whole steps towards where it starts by the core's "
                 "floor_div, leaves them less than a step apart and the rotor not past C: n moves of angle a end "
                 "within one step of n a. Stated relative to s (floor_div(x + 360 s) = floor_div(x) + s)",
                 [](unsigned ms) {
                   z3::context& c = shared_context();
                   const auto v = [&](std::int64_t x) { return c.bv_val(x, 24); };
                   const z3::expr g = c.bv_const("gap", 24);
                   const z3::expr a = c.bv_const("angle", 24);
                   const z3::expr spr = c.bv_const("steps_per_turn", 24);
                   const z3::expr right = c.bool_const("right");
                   const z3::expr pre = z3::sgt(g, v(-360)) && z3::slt(g, v(360)) && z3::ule(a, v(9999)) &&
                                        (spr == v(40) || spr == v(80));
                   const z3::expr x = z3::ite(right, g + a * spr, g - a * spr);  // C after the move, relative to 360 s
                   // floor_div(x, 360) of core/hc08_motor: x >= 0 ? x / 360 : -((-x + 359) / 360); the
                   // dividend is non-negative in each branch, so the division is unsigned.
                   const auto floor_div = [&](const z3::expr& y) {
                     return z3::ite(z3::sge(y, v(0)), z3::udiv(y, v(360)), -z3::udiv(-y + v(359), v(360)));
                   };
                   const z3::expr to = z3::ite(right, floor_div(x), -floor_div(-x));
                   const z3::expr gap = x - v(360) * to;
                   const z3::expr claim = z3::implies(pre, z3::sgt(gap, v(-360)) && z3::slt(gap, v(360)) &&
                                                               z3::ite(right, z3::sge(gap, v(0)), z3::sle(gap, v(0))));
                   return check_valid(c, claim, ms, {{"gap", g}, {"angle", a}, {"steps_per_turn", spr}, {"right", right}});
                 }});
  return out;
}

}  // namespace ap::model::smt
