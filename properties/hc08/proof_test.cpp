// The hc08 profile's proof obligations (models/smt/src/hc08_obligations.cpp), each PROVED, and
// the arithmetic they state checked against the core's, so the proofs speak about the code that
// runs: the ramp (core/hc08/timer) on every period the ramp can hold, mode B's position
// (core/hc08/motor) on random sequences of moves, drive changes and stopped runs of a real Motor.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "core/hc08/motor/motor.hpp"
#include "core/hc08/timer/timer.hpp"
#include "models/smt/arith.hpp"
#include "models/hc08/obligations.hpp"
#include "models/smt/obligation.hpp"

namespace {

namespace smt = ap::model::smt;
namespace t = ap::hc08_timer;
using ap::hc08_drive::Drive;

TEST(Hc08Proofs, EveryObligationIsProved) {
  const auto list = smt::hc08_obligations();
  ASSERT_EQ(list.size(), 7U);
  // A name prefix (AP_PROVE_ONLY, docs/proofs.md): the hc08 proof mutants'
  // Killed-by checks prove only the obligations they plant a bug under; one that names nothing
  // fails.
  const char* only = std::getenv("AP_PROVE_ONLY");
  std::size_t selected = 0;
  for (const auto& o : list) {
    if (only != nullptr && o.name.rfind(only, 0) != 0) continue;
    ++selected;
    const auto r = smt::run(o, 60000);
    EXPECT_EQ(r.verdict, smt::Verdict::Proved) << o.name << ": " << r.counterexample;
    std::printf("%-40s %-7s %.2f s\n", o.name.c_str(), smt::verdict_name(r.verdict), r.seconds);
  }
  EXPECT_GT(selected, 0U) << "AP_PROVE_ONLY=" << only << " names no hc08 obligation";
}

std::uint64_t eval(const z3::expr& e) { return e.simplify().get_numeral_uint64(); }

TEST(Hc08Proofs, TheStatedRampIsTheCoresOnEveryPeriod) {
  z3::context& c = smt::shared_context();
  for (const Drive d : {Drive::Full, Drive::Half}) {
    const std::uint16_t start = t::tmod_at_hz(t::start_hz(d));
    const std::uint16_t fastest = t::tmod_at_hz(t::max_hz(d));
    for (std::uint32_t now = fastest; now <= start; now += 7) {
      ASSERT_EQ(eval(smt::hc08_steps_to_start(c, c.bv_val(now, 32), d)), t::steps_to_start(static_cast<std::uint16_t>(now), d));
      for (std::uint32_t target = fastest; target <= start; target += 97) {
        for (const bool stopping : {false, true}) {
          const auto core = t::ramp_step(static_cast<std::uint16_t>(now), static_cast<std::uint16_t>(target), stopping, d);
          const auto stated = eval(smt::hc08_ramp_step_term(c, c.bv_val(now, 32), c.bv_val(target, 32), c.bool_val(stopping), d));
          ASSERT_EQ(stated, core) << now << " " << target << " " << stopping;
        }
      }
    }
  }
}

namespace mo = ap::hc08_motor;
using ap::model::smt::Arith;
using ap::model::smt::Check;
using ap::model::smt::Checks;
using ap::model::smt::Sem;

// The mirror's state as plain values, and as terms of either semantics.
struct ModeB {
  std::int64_t commanded = 0;
  std::int64_t half = 0;
  bool from_rotor = false;
  bool full = true;  // power-up: four-step
};

struct Terms {
  z3::context& c;
  Sem sem;
  z3::expr i64(std::int64_t x) const { return sem == Sem::Bv ? c.bv_val(x, 64) : c.int_val(x); }
  z3::expr u16(std::uint16_t x) const { return sem == Sem::Bv ? c.bv_val(static_cast<unsigned>(x), 16) : c.int_val(x); }
  smt::Hc08ModeBState state(const ModeB& m) const {
    return {i64(m.commanded), i64(m.half), c.bool_val(m.from_rotor), c.bool_val(m.full)};
  }
  std::int64_t value(const z3::expr& e) const {
    const z3::expr v = e.simplify();
    return v.is_bv() ? static_cast<std::int64_t>(v.get_numeral_uint64()) : v.get_numeral_int64();
  }
  ModeB values(const smt::Hc08ModeBState& s) const {
    return {value(s.commanded), value(s.half), s.from_rotor.simplify().is_true(), s.full.simplify().is_true()};
  }
  // The Int twin's side conditions (hc08.mode_b.no_overflow) on these concrete values: each
  // holds. (The Bv records are Z3's no-overflow predicates, which simplify() leaves unevaluated.)
  void all_hold(const Checks& checks) const {
    if (sem != Sem::Int) return;
    for (const auto& k : checks) EXPECT_TRUE(z3::implies(k.guard, k.cond).simplify().is_true()) << k.name;
  }
};

// Mode B's position arithmetic as the obligations state it (hc08_mode_b_move_term,
// hc08_set_drive_term), bit-precise and its Int twin, against a real Motor: random moves (angles
// weighted to 0, a few degrees, the steps' edges and 9999; either way; either drive type, so
// start() changes it), some stopped early, drive changes at rest and mode A runs, the mirror's
// state carried from event to event. commanded_ is private: the mirror's is compared through
// what it decides, the steps of every later move (remaining() and the position), so a carried
// remainder that differs shows up.
void mode_b_against_the_core(Sem sem) {
  ASSERT_EQ(mo::kAngleMax, 9999U);  // the bound the obligations assume
  const Terms tm{smt::shared_context(), sem};
  z3::context& c = tm.c;
  std::mt19937 rng(0x0b08);
  const auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  const std::uint16_t angles[] = {0, 1, 2, 3, 4, 5, 8, 9, 10, 13, 45, 90, 359, 360, 361, 9998, 9999};
  std::size_t moves = 0, behind = 0, drive_changes = 0, forward = 0, stopped = 0;
  for (int seq = 0; seq < 60; ++seq) {
    mo::Motor m;
    ModeB s;
    for (int ev = 0; ev < 40; ++ev) {
      const int kind = pick(10);
      const bool full = pick(2) == 0;
      const Drive d = full ? Drive::Full : Drive::Half;
      const bool right = pick(2) == 0;
      if (kind < 6) {  // a mode B move, sometimes stopped
        const std::uint16_t angle = pick(3) == 0 ? angles[pick(sizeof angles / sizeof angles[0])]
                                                 : static_cast<std::uint16_t>(pick(kind == 0 ? 10000 : 40));
        mo::Settings st;
        st.mode = mo::Mode::B;
        st.drive = d;
        st.right = right;
        st.speed_centi = 100;
        st.angle_deg = angle;
        Checks checks;
        const smt::Hc08ModeBMove mv =
            smt::hc08_mode_b_move_term(c, tm.state(s), tm.u16(angle), c.bool_val(right), c.bool_val(full), sem, &checks);
        tm.all_hold(checks);
        const std::int64_t half_before = m.position_half();
        ASSERT_EQ(m.start(st), mo::Error::None);
        const std::uint32_t planned = m.remaining();
        ASSERT_EQ(tm.value(mv.remaining), planned) << "seq " << seq << " event " << ev << " angle " << angle;
        const std::int64_t n = tm.value(mv.steps);
        if (planned > 0) {
          ASSERT_EQ(mv.right.simplify().is_true(), m.dir() > 0);
        }
        if (n < 0) ++behind;                        // a remainder behind the rotor: nothing turns
        if (m.position_half() != half_before) ++forward;  // start()'s drive change moved the rotor
        const bool stop_early = planned > 2 && pick(4) == 0;
        const std::uint32_t stop_at = stop_early ? static_cast<std::uint32_t>(pick(static_cast<int>(planned) - 1)) : planned;
        std::uint32_t done = 0;
        while (m.running()) {
          if (stop_early && done == stop_at) m.stop();
          m.on_match();
          ++done;
        }
        ++moves;
        if (done == planned) {  // the whole move
          s = tm.values(mv.after);
          ASSERT_EQ(s.half, m.position_half()) << "seq " << seq << " event " << ev;
        } else {  // stopped early (at the start frequency: the next step): the next move counts from the rotor
          ASSERT_EQ(done, stop_at + 1);
          ++stopped;
          s = {tm.value(mv.after.commanded), m.position_half(), true, full};
        }
      } else if (kind < 9) {  // a drive change at rest
        Checks checks;
        s = tm.values(smt::hc08_set_drive_term(c, tm.state(s), c.bool_val(full), sem, &checks));
        tm.all_hold(checks);
        ASSERT_TRUE(m.set_drive(d));
        ASSERT_EQ(s.half, m.position_half()) << "seq " << seq << " event " << ev;
        ++drive_changes;
      } else {  // a mode A run, stopped: start() changes the drive type first
        s = tm.values(smt::hc08_set_drive_term(c, tm.state(s), c.bool_val(full), sem, nullptr));
        mo::Settings st;
        st.mode = mo::Mode::A;
        st.drive = d;
        st.right = right;
        st.speed_centi = 100;
        ASSERT_EQ(m.start(st), mo::Error::None);
        ASSERT_EQ(s.half, m.position_half());
        const int steps = pick(12);
        for (int i = 0; i < steps && m.running(); ++i) m.on_match();
        m.stop();
        while (m.running()) m.on_match();
        s = {s.commanded, m.position_half(), true, full};
      }
    }
  }
  // The sequences reach the cases the arithmetic is about.
  EXPECT_GT(moves, 1000U);
  EXPECT_GT(behind, 10U);
  EXPECT_GT(drive_changes, 300U);
  EXPECT_GT(forward, 10U);
  EXPECT_GT(stopped, 50U);
}

TEST(Hc08Proofs, TheStatedModeBArithmeticIsTheCores) { mode_b_against_the_core(Sem::Bv); }
TEST(Hc08Proofs, TheIntTwinOfModeBIsTheCores) { mode_b_against_the_core(Sem::Int); }

}  // namespace
