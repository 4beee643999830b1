// The HC08 unit's obligations (docs/hc08.md "Ramp", "Mode B", "Angle arithmetic"), over the
// core's constants (core/hc08/timer: start frequencies, kAccelStep, tmod_at_hz). The ramp's
// arithmetic is stated here as the core writes it (ramp_step, steps_to_start, the mode B choice
// of Motor::on_match); hc08_ramp_step_term() is also what the conformance test
// (properties/hc08/proof_test.cpp) evaluates against the core on concrete values. Mode B's
// position arithmetic (Motor::start, on_match, set_drive of core/hc08/motor) is mirrored the
// same way, over the motor's fields at their C++ widths: hc08_set_drive_term() and
// hc08_mode_b_move_term(), checked against a real Motor by the same test. This file and
// core/hc08/motor/src/motor.cpp must change together.
#include <chrono>
#include <cstdint>
#include <limits>
#include <string>

#include "core/hc08/drive/drive.hpp"
#include "core/hc08/timer/timer.hpp"
#include "models/smt/arith.hpp"
#include "models/hc08/obligations.hpp"
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

// ---- Mode B's position: a mirror of core/hc08/motor/src/motor.cpp -------------------------
// Written once over the proof kit's Arith (models/smt/arith.hpp): Sem::Bv is
// the motor's int64 fields as 64-bit two's complement (what the C++ computes; the conformance
// test evaluates it against a real Motor), Sem::Int the same text over integers, each int64
// operation recording "the exact result fits int64" (a division "dividend >= 0, divisor > 0",
// the uint32 cast "0 <= n < 2^32"). hc08.mode_b.no_overflow proves every record on the states
// the claims start from, so there the two compute the same values, and the claims are decided
// on the Int twin (QF_LIA: every product is by a constant; 64-bit dividers and multipliers made
// the same claims time out in QF_BV). Three exact rewrites of the C++ text, in both:
//   x * dir (dir = +-1) is a select of x and -x (so is the 64-bit product, bit for bit);
//   x / (Full ? 720 : 360) and x * (Full ? 2 : 1) select between the two constant forms;
//   on_match's `half_ += dir() * k`, `remaining_` times, is half_ + dir * (k * remaining_):
//   the intermediate positions lie between the first and the last, so the last fitting int64
//   (recorded) means none wrapped.

namespace {

z3::expr times_dir(const Arith& ar, const z3::expr& right, const z3::expr& x, const std::string& name) {
  return z3::ite(right, x, ar.under(!right).sub(ar.lit(0), x, name));
}

z3::expr odd(const Arith& ar, const z3::expr& x) {
  return ar.sem == Sem::Bv ? x.extract(0, 0) == ar.c.bv_val(1, 1) : z3::mod(x, ar.c.int_val(2)) == ar.c.int_val(1);
}

}  // namespace

// Motor::set_drive at rest: `if (d == seq_.drive()) return true; half_ += seq_.set_drive(d);`.
// The sequencer moves the rotor (returns 1: half a step forward) only from half step to full
// step on a pattern full step lacks. Power-up is full step's first pattern at half_ = 0 and
// every half step moves one pattern of the half-step table, so the patterns full step has are
// exactly those at an even half_ (two-phase and wave alike): set_drive returns 1 exactly when
// half_ is odd (checked against the sequencer by the conformance test). commanded_ is not
// touched: a drive change keeps it (docs/hc08.md "Angle arithmetic").
Hc08ModeBState hc08_set_drive_term(z3::context& c, const Hc08ModeBState& s, const z3::expr& full, Sem sem,
                                   Checks* checks) {
  const Arith ar(c, sem, checks, c.bool_val(true));
  const z3::expr forward = full && !s.full && odd(ar, s.half);
  return {s.commanded, z3::ite(forward, ar.under(forward).add(s.half, ar.lit(1), "set_drive.half+1"), s.half),
          s.from_rotor, full};
}

// Motor::start in mode B (angle <= kAngleMax, a speed the timer makes), then every one of its
// remaining_ steps (Motor::on_match), line for line:
//   set_drive(s.drive);
//   if (from_rotor_) commanded_ = half_ * 360;  from_rotor_ = false;
//   dir = right_ ? 1 : -1;  commanded_ += dir * (int64)angle_deg * 80;
//   unit = Full ? 720 : 360;  n = floor_div(dir * (commanded_ - half_ * 360), unit);
//     floor_div(a, b) = a >= 0 ? a / b : -((-a + b - 1) / b)
//   remaining_ = (uint32)(n > 0 ? n : 0);  right_ unchanged;
//   remaining_ times: half_ += dir() * (Full ? 2 : 1).
Hc08ModeBMove hc08_mode_b_move_term(z3::context& c, const Hc08ModeBState& before, const z3::expr& angle,
                                    const z3::expr& right, const z3::expr& full, Sem sem, Checks* checks) {
  const Arith ar(c, sem, checks, c.bool_val(true));
  const bool bv = sem == Sem::Bv;
  const Hc08ModeBState s = hc08_set_drive_term(c, before, full, sem, checks);
  const z3::expr here = ar.mul(s.half, ar.lit(360), "start.half*360");
  const z3::expr angle64 = bv ? z3::zext(angle, 48) : angle;
  const z3::expr commanded = ar.add(z3::ite(s.from_rotor, here, s.commanded),
                                    ar.mul(times_dir(ar, right, angle64, "start.dir*angle"), ar.lit(80), "start.*80"),
                                    "start.commanded+=");
  const z3::expr unit = z3::ite(full, ar.lit(720), ar.lit(360));
  const z3::expr a = times_dir(ar, right, ar.sub(commanded, here, "start.commanded-here"), "start.dir*gap");
  const auto div_unit = [&](const Arith& in, const z3::expr& x, const std::string& name) {
    return z3::ite(full, in.under(full).div(x, in.lit(720), name), in.under(!full).div(x, in.lit(360), name));
  };
  const z3::expr nonneg = a >= ar.lit(0);
  const Arith neg = ar.under(!nonneg);
  const z3::expr up = neg.sub(neg.add(neg.sub(neg.lit(0), a, "floor_div.-a"), unit, "floor_div.-a+b"), neg.lit(1),
                              "floor_div.-a+b-1");
  const z3::expr n = z3::ite(nonneg, div_unit(ar.under(nonneg), a, "floor_div.a/b"),
                             neg.sub(neg.lit(0), div_unit(neg, up, "floor_div.(-a+b-1)/b"), "floor_div.-q"));
  const z3::expr clamped = z3::ite(n > ar.lit(0), n, ar.lit(0));
  // static_cast<std::uint32_t>: the low 32 bits; in Int the value, recorded as fitting.
  ar.record("start.(uint32)n", clamped >= ar.lit(0) && clamped <= ar.lit(std::int64_t{0xFFFFFFFF}));
  const z3::expr remaining = bv ? clamped.extract(31, 0) : clamped;
  const z3::expr rem64 = bv ? z3::zext(remaining, 32) : remaining;
  const z3::expr turned = z3::ite(full, ar.mul(rem64, ar.lit(2), "on_match.2*remaining"), rem64);
  const z3::expr half = ar.add(s.half, times_dir(ar, right, turned, "on_match.dir*turned"), "on_match.half+=");
  return {{commanded, half, c.bool_val(false), full}, remaining, right, n};
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


// ---- Mode B's position: the obligations, on the Int twin --------------------------------

// hyps -> goal in QF_LIA; FAILED with the shown terms, and FAILED ("vacuous") when the
// hypotheses alone have no model (a proof from them would say nothing).
Outcome decide_lia(z3::context& c, const z3::expr& hyps, const z3::expr& goal, unsigned ms, const Shown& show) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto solver = [&] {
    z3::solver s(c, "QF_LIA");
    if (ms > 0) s.set("timeout", ms);
    s.add(hyps);
    return s;
  };
  z3::solver s = solver();
  s.add(!goal);
  const z3::check_result r = s.check();
  const z3::check_result vac = r == z3::unsat ? solver().check() : z3::sat;
  Outcome out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r == z3::unsat && vac == z3::sat) {
    out.verdict = Verdict::Proved;
  } else if (r == z3::unsat && vac == z3::unsat) {
    out.verdict = Verdict::Failed;
    out.counterexample = "vacuous: the hypotheses have no model, so the proof would say nothing";
  } else if (r == z3::sat) {
    out.verdict = Verdict::Failed;
    out.counterexample = shown_in(s.get_model(), show);
  } else {
    out.verdict = Verdict::Unknown;
    out.counterexample = r == z3::unknown ? s.reason_unknown() : "hypotheses: unknown";
  }
  return out;
}

// hc08_motor::kAngleMax (start() refuses more: four digits); the conformance test checks it is.
constexpr std::int64_t kAngleMax = 9999;
constexpr std::int64_t kHalfBound = std::int64_t{1} << 40;  // |half_|: 2^40 half steps, > 20 000 years at 1700 Hz

// One event from a state at rest, on the Int twin: the state's fields in their C++ ranges
// (int64, angle_deg uint16), the ghost `asked`, and what a mode B move, a drive change and a
// stopped run make of it.
struct ModeBEvent {
  z3::context& c;
  Checks checks;
  Hc08ModeBState s;
  z3::expr asked, angle, right, full, run_steps;
  Hc08ModeBMove move;
  Hc08ModeBState started;  // after a drive change at rest, or start()'s: where the move starts
  Hc08ModeBState ran;      // start(), then steps either way (net run_steps), stopped
  z3::expr asked_after;    // the ghost after the move

  explicit ModeBEvent(z3::context& ctx)
      : c(ctx),
        s{c.int_const("commanded"), c.int_const("half"), c.bool_const("from_rotor"), c.bool_const("full")},
        asked(c.int_const("asked")), angle(c.int_const("angle")), right(c.bool_const("right")),
        full(c.bool_const("to_full")), run_steps(c.int_const("run_steps")),
        move(hc08_mode_b_move_term(c, s, angle, right, full, Sem::Int, &checks)),
        started(hc08_set_drive_term(c, s, full, Sem::Int, nullptr)),
        ran{started.commanded, started.half + z3::ite(full, c.int_val(2) * run_steps, run_steps), c.bool_val(true), full},
        asked_after(z3::ite(s.from_rotor, started.half * c.int_val(360), asked) +
                    signed_(angle) * c.int_val(80)) {}

  // dir * x, dir = right ? 1 : -1 (spec side: integers, nothing to wrap).
  z3::expr signed_(const z3::expr& x) const { return z3::ite(right, x, -x); }

  z3::expr i64(const z3::expr& x) const {
    return x >= c.int_val(std::numeric_limits<std::int64_t>::min()) && x <= c.int_val(std::numeric_limits<std::int64_t>::max());
  }
  // Mode B's position at rest (after power-up, a whole move, a drive change, or a stopped run):
  // the rotor is on the drive type's rest positions (full step: an even half_); and unless the
  // next move counts from the rotor (from_rotor_), the commanded position is the ghost `asked`
  // (where mode B last counted from, plus every angle asked since, in 1/80 degree) and the rotor
  // is less than a full step (720) from it, less than a half step (360) when it stands on a
  // position only half step has (where a change to full step moves it half a step forward).
  z3::expr at_rest(const Hc08ModeBState& t, const z3::expr& ghost) const {
    const z3::expr gap = t.commanded - t.half * c.int_val(360);
    const z3::expr even = z3::mod(t.half, c.int_val(2)) == c.int_val(0);
    const auto within = [&](int w) { return gap > c.int_val(-w) && gap < c.int_val(w); };
    return z3::implies(t.full, even) &&
           z3::implies(!t.from_rotor, t.commanded == ghost && within(720) && z3::implies(!t.full && !even, within(360)));
  }
  // The states the claims start from: fields in range, at rest, |half_| <= 2^40, an angle start()
  // takes. (A stopped run: any whole number of steps of the drive type, net, either way.)
  z3::expr pre() const {
    return i64(s.commanded) && i64(s.half) && i64(asked) && at_rest(s, asked) && s.half >= c.int_val(-kHalfBound) &&
           s.half <= c.int_val(kHalfBound) && angle >= c.int_val(0) && angle <= c.int_val(kAngleMax);
  }
  Shown shown() const {
    return {{"commanded", s.commanded}, {"half", s.half}, {"from_rotor", s.from_rotor}, {"full", s.full},
            {"asked", asked}, {"angle", angle}, {"right", right}, {"to_full", full},
            {"n", move.steps}, {"remaining", move.remaining}, {"commanded'", move.after.commanded},
            {"half'", move.after.half}, {"asked'", asked_after}, {"half after a drive change", started.half}};
  }
};

void add_mode_b_position(ObligationList& out) {
  out.push_back(
      {"hc08.mode_b.no_overflow",
       "QF_LIA on the Int twin of the mode B mirror (hc08_mode_b_move_term, hc08_set_drive_term): from every "
       "state the claims below start from (the no_drift invariant, |half_| <= 2^40, angle 0..9999, either way, "
       "either drive type), every int64 operation of start()'s arithmetic, its drive change and the move's "
       "steps has its exact result in int64, each division a non-negative dividend, and n > 0 ? n : 0 fits "
       "the uint32 remaining_ (n <= (720 + 9999 * 80) / 360); so the Int twin computes what the C++ does",
       [](unsigned ms) {
         z3::context& c = shared_context();
         const ModeBEvent e(c);
         z3::expr all = c.bool_val(true);
         for (const auto& k : e.checks) all = all && z3::implies(k.guard, k.cond);
         return decide_lia(c, e.pre(), all, ms, e.shown());
       }});
  out.push_back(
      {"hc08.mode_b.no_drift",
       "QF_LIA on the Int twin, 1-induction over the events at rest: a whole mode B move of any angle 0..9999 "
       "either way in either drive type (start() changing the drive type first), a drive change at rest, a run "
       "stopped after any number of steps either way (mode A with its reversals, a move stopped early: the next "
       "move counts from the rotor). "
       "Invariant (base: power-up) the commanded position is the ghost `asked` (where mode B last counted "
       "from plus every angle asked since, 1/80 degree, whatever drive changes came between: a drive change "
       "keeps it) and the rotor is less than a full step (720) from it, less than a half step on a position only "
       "half step has; full step on even half_. So n moves of angle a end within a full step of n a, across drive "
       "changes",
       [](unsigned ms) {
         z3::context& c = shared_context();
         const ModeBEvent e(c);
         const Hc08ModeBState power_up{c.int_val(0), c.int_val(0), c.bool_val(false), c.bool_val(true)};
         const z3::expr goal = e.at_rest(power_up, c.int_val(0)) && e.at_rest(e.move.after, e.asked_after) &&
                               e.at_rest(e.started, e.asked) && e.at_rest(e.ran, e.asked);
         return decide_lia(c, e.pre(), goal, ms, e.shown());
       }});
  out.push_back(
      {"hc08.mode_b.never_against_direction",
       "QF_LIA on the Int twin, from every state of the no_drift invariant: a mode B move never steps against its "
       "direction: right_ stays the direction asked, remaining_ >= 0 and dir * (half' - half) >= 0 "
       "from where it starts (after start()'s drive change, whose forward half step is not the move's); and it "
       "never passes the commanded position (a move that steps ends with dir * (commanded' - 360 half') >= 0). "
       "A remainder carried behind the rotor turns nothing",
       [](unsigned ms) {
         z3::context& c = shared_context();
         const ModeBEvent e(c);
         const z3::expr steps = e.move.remaining > c.int_val(0);
         const z3::expr goal = e.move.right == e.right && e.move.remaining >= c.int_val(0) &&
                               e.signed_(e.move.after.half - e.started.half) >= c.int_val(0) &&
                               z3::implies(steps, e.signed_(e.move.after.commanded - e.move.after.half * c.int_val(360)) >=
                                                      c.int_val(0));
         return decide_lia(c, e.pre(), goal, ms, e.shown());
       }});
}

}  // namespace

ObligationList hc08_obligations() {
  ObligationList out;
  add_mode_b_ramp(out, Drive::Full);
  add_mode_b_ramp(out, Drive::Half);
  add_stop(out, Drive::Full);
  add_stop(out, Drive::Half);
  add_mode_b_position(out);
  return out;
}

}  // namespace ap::model::smt
