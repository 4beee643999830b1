// Unit tests of the axis core: step timer (G17), units, start position (eq. 7-2, G18),
// watchdog (G15), the transition table (totality/determinism), commands, safety stops.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <set>

#include "axis_harness.hpp"
#include "core/xy/axis/axis.hpp"
#include "core/xy/axis/position.hpp"
#include "core/xy/axis/step_timer.hpp"
#include "core/xy/axis/units.hpp"
#include "core/xy/axis/watchdog.hpp"

using namespace ap::xy_axis;

namespace {

// The thesis's literal eq. 7-4/7-5 (floor division), kept only to show the defect of G17.
struct Literal {
  int64_t psc;
  int64_t arr;
  bool div_by_zero;
};
Literal thesis_literal(int64_t f) {
  const int64_t clk = kTimerClockHz;
  const int64_t psc = clk / (f * 65536) - 1;
  if (psc + 1 == 0) {
    return {psc, 0, true};
  }
  return {psc, clk / (f * (psc + 1)) - 1, false};
}

State homed_at(int32_t pos) {
  State s;
  s.pos = pos;
  s.target = pos;
  s.homed = 1;
  return s;
}

// Runs ticks with a fixed input (the command only in the first tick).
StepResult run(State& s, const Config& c, Input in, int ticks) {
  StepResult r{s, {}};
  for (int i = 0; i < ticks; ++i) {
    r = step(s, in, c);
    s = r.state;
    in.cmd = Command{};
  }
  return r;
}

}  // namespace

// ---- step timer -------------------------------------------------------------------------

TEST(AxisTimer, SeedVectors) {
  const std::array<std::array<uint32_t, 3>, 6> v = {{
      {1000, 1, 39999}, {1221, 0, 65519}, {1, 1220, 65519}, {51200, 0, 1561}, {100, 12, 61537}, {10000, 0, 7999}}};
  for (const auto& x : v) {
    const auto t = step_timer(x[0]);
    ASSERT_TRUE(t.has_value()) << x[0];
    EXPECT_EQ(t->psc, x[1]) << x[0];
    EXPECT_EQ(t->arr, x[2]) << x[0];
  }
  EXPECT_FALSE(step_timer(0).has_value());
  EXPECT_FALSE(step_timer(kStepFreqMax + 1).has_value());
}

TEST(AxisTimer, ThesisLiteralFormulaIsBroken) {
  // What the corrected function fixes: ARR overflow below 1220.7 Hz, PSC = -1 above it.
  EXPECT_EQ(thesis_literal(1000).psc, 0);
  EXPECT_EQ(thesis_literal(1000).arr, 79999);
  EXPECT_GT(thesis_literal(1).arr, 65535);
  EXPECT_EQ(thesis_literal(2000).psc, -1);
  EXPECT_TRUE(thesis_literal(2000).div_by_zero);
}

// Every integer frequency the axis can ask for (1 .. kSpeedMax usteps/s), plus a sweep up to
// the timer's own limit: registers fit, the realised frequency never undershoots, the relative
// error is below 1/(ARR+1), and no smaller prescaler would have fitted (best resolution).
TEST(AxisTimer, ExhaustiveErrorBound) {
  const uint64_t clk = kTimerClockHz;
  uint64_t worst_ppb = 0;
  const auto check = [&](uint32_t f) {
    const auto t = step_timer(f);
    ASSERT_TRUE(t.has_value()) << f;
    const uint64_t psc1 = uint64_t{t->psc} + 1;
    const uint64_t arr1 = uint64_t{t->arr} + 1;
    ASSERT_GE(t->arr, 1u) << f;
    ASSERT_GE(clk, f * psc1 * arr1) << f;            // f_real >= f
    ASSERT_LT(clk, f * psc1 * (arr1 + 1)) << f;      // f_real < f (ARR+2)/(ARR+1)
    if (t->psc > 0) {
      ASSERT_GT(clk, f * (psc1 - 1) * 65536) << f;   // PSC-1 would overflow ARR
    }
    const uint64_t ppb = (clk - f * psc1 * arr1) * 1'000'000'000ull / (f * psc1 * arr1);
    worst_ppb = std::max(worst_ppb, ppb);
  };
  for (uint32_t f = 1; f <= static_cast<uint32_t>(kSpeedMax); ++f) {
    check(f);
  }
  EXPECT_LT(worst_ppb, 12'500'000u);  // < 1/80 at the top speed
  for (uint32_t f = static_cast<uint32_t>(kSpeedMax); f <= kStepFreqMax; f += 997) {
    check(f);
  }
  check(kStepFreqMax);
}

TEST(AxisTimer, ErrorBelow51200HzIsTiny) {
  for (uint32_t f = 1; f <= 51200; ++f) {
    const auto t = step_timer(f);
    ASSERT_TRUE(t.has_value());
    // |f_real - f| / f < 1/1562 for every f the thesis's 256-microstep range needs.
    ASSERT_LT((realised_mhz(*t) - uint64_t{f} * 1000) * 1562, uint64_t{f} * 1000) << f;
  }
}

// ---- units ------------------------------------------------------------------------------

TEST(AxisUnits, Conversions) {
  const Mechanics m{};  // 2 mm pitch, 200 x 16 -> 1.6 usteps/um
  EXPECT_EQ(um_to_usteps(20000, m, Round::Nearest).value, 32000);
  EXPECT_EQ(speed_to_usteps(10000, m).value, 16000);
  EXPECT_EQ(accel_to_usteps(20000, m).value, 32000);  // the thesis's 20000 um/s^2
  EXPECT_EQ(accel_to_usteps(5000, m).value, 8000);
  EXPECT_EQ(um_to_usteps(1, m, Round::Nearest).value, 2);   // 1.6
  EXPECT_EQ(um_to_usteps(1, m, Round::Down).value, 1);
  EXPECT_EQ(um_to_usteps(-1, m, Round::Down).value, -2);
  EXPECT_EQ(um_to_usteps(-1, m, Round::Up).value, -1);
  EXPECT_EQ(um_to_usteps(-1, m, Round::Nearest).value, -2);
  EXPECT_EQ(usteps_to_um(32000, m), 20000);
  EXPECT_EQ(speed_to_usteps(-1, m).error, Error::BadCommand);
  EXPECT_EQ(accel_to_usteps(0, m).error, Error::BadCommand);
  EXPECT_EQ(um_to_usteps(1, Mechanics{0, 200, 16}, Round::Nearest).error, Error::BadConfig);
  EXPECT_EQ(um_to_usteps(999999, Mechanics{1, 1000, 256}, Round::Nearest).error, Error::OutOfLimits);
}

RC_GTEST_PROP(AxisUnits, TargetsNeverPastTravelLimits, ()) {
  const Mechanics m{*rc::gen::inRange<int32_t>(1, 100'001), *rc::gen::inRange<int32_t>(1, 1001),
                    *rc::gen::inRange<int32_t>(1, 257)};
  const int32_t a = *rc::gen::inRange<int32_t>(-1'000'000, 1'000'000);
  const int32_t b = *rc::gen::inRange<int32_t>(-1'000'000, 1'000'000);
  const int32_t lo_um = std::min(a, b);
  const int32_t hi_um = std::max(a, b);
  const int32_t um = *rc::gen::inRange<int32_t>(-1'100'000, 1'100'000);
  const UstepLimits lim = limits_to_usteps(lo_um, hi_um, m);
  const Converted t = target_to_usteps(um, lo_um, hi_um, m);
  const long double scale = static_cast<long double>(usteps_per_rev(m)) / m.pitch_um;
  if (lim.error == Error::None) {
    // Inward rounding: the ustep limits lie within the um limits.
    RC_ASSERT(lim.min >= static_cast<long double>(lo_um) * scale - 1e-6L);
    RC_ASSERT(lim.max <= static_cast<long double>(hi_um) * scale + 1e-6L);
  }
  if (um < lo_um || um > hi_um) {
    RC_ASSERT(t.error == Error::OutOfLimits);
  } else if (t.error == Error::None) {
    RC_ASSERT(lim.error == Error::None);
    RC_ASSERT(t.value >= lim.min && t.value <= lim.max);
    // Off by at most one ustep from the exact conversion (rounding, or the pull-back).
    RC_ASSERT(std::abs(static_cast<long double>(t.value) - um * scale) <= 1.0L + 1e-6L);
  }
}

// ---- start position (eq. 7-2) -----------------------------------------------------------

TEST(AxisPosition, Equation72Vectors) {
  EXPECT_EQ(encoder_to_usteps({3, 8192, 1}, 3200).pos, 11200);
  EXPECT_EQ(encoder_to_usteps({0, 16383, 1}, 51200).pos, 51196);
  EXPECT_EQ(encoder_to_usteps({-1, 8192, 1}, 3200).pos, -1600);
  EXPECT_EQ(encoder_to_usteps({-1, 0, 1}, 3200).pos, -3200);
  // 65535 turns x 51200 overflows int32 in the thesis's types; here it is a typed error.
  EXPECT_EQ(encoder_to_usteps({65535, 0, 1}, 51200).error, Error::OutOfLimits);
  EXPECT_EQ(encoder_to_usteps({0, 16384, 1}, 3200).error, Error::BadCommand);
}

TEST(AxisPosition, SourcePriority) {
  const EncoderReading enc{2, 0, 1};
  const EncoderReading bad_enc{2, 0, 0};
  EXPECT_EQ(start_position(&enc, {777, 1}, 3200).pos, 6400);
  EXPECT_EQ(start_position(&bad_enc, {777, 1}, 3200).pos, 777);
  EXPECT_EQ(start_position(nullptr, {777, 1}, 3200).pos, 777);
  const StartPosition none = start_position(nullptr, {777, 0}, 3200);
  EXPECT_EQ(none.error, Error::NotHomed);
  EXPECT_EQ(initial_state(none).homed, 0);
  EXPECT_EQ(initial_state(start_position(&enc, {}, 3200)).homed, 1);
}

// ---- watchdog (G15) ---------------------------------------------------------------------

TEST(AxisWatchdog, ThreePeriods) {
  LinkWatchdog w;
  EXPECT_FALSE(link_alive(w));
  w = watchdog_tick(w, true);
  for (int i = 1; i < kLinkTimeoutTicks; ++i) {
    w = watchdog_tick(w, false);
    ASSERT_TRUE(link_alive(w)) << i;
  }
  w = watchdog_tick(w, false);
  EXPECT_FALSE(link_alive(w));
  for (int i = 0; i < 70000; ++i) {
    w = watchdog_tick(w, false);  // saturates, never wraps back to alive
  }
  EXPECT_FALSE(link_alive(w));
  EXPECT_TRUE(link_alive(watchdog_tick(w, true)));
}

TEST(AxisWatchdog, LinkLossStopsJogWithDeceleration) {
  Config c;
  State s = homed_at(100'000);
  LinkWatchdog w;
  Input in;
  int32_t prev_v = 0;
  int silent = 0;
  for (int t = 0; t < 6000; ++t) {
    const bool send = t < 3000 && t % 100 == 0;  // the PC stops sending at t = 3 s
    w = watchdog_tick(w, send);
    in.cmd = send ? Command{CmdKind::Jog, 1, 1, 0} : Command{};
    in.link_alive = link_alive(w) ? 1 : 0;
    silent = send ? 0 : silent + 1;
    const StepResult r = step(s, in, c);
    if (r.state.v != 0 && prev_v != 0) {
      ASSERT_LE(std::abs(r.state.v - prev_v), c.accel) << t;  // braked, not cut
    }
    if (silent < kLinkTimeoutTicks - 1) {
      ASSERT_EQ(r.state.mode, Mode::Jog) << t;
    }
    prev_v = r.state.v;
    s = r.state;
  }
  EXPECT_EQ(s.phase, Phase::Stop);
  EXPECT_EQ(s.mode, Mode::Idle);
}

// ---- transition table -------------------------------------------------------------------

TEST(AxisTable, ExactlyOneTransitionPerPhaseAndClass) {
  std::set<char> used;
  for (int p = 0; p < kPhaseCount; ++p) {
    for (int k = 0; k < kClassCount; ++k) {
      const auto ph = static_cast<Phase>(p);
      const auto cl = static_cast<Class>(k);
      int holding = 0;
      Edge which = Edge::X;
      for (int e = 0; e < kEdgeCount; ++e) {
        if (edge_guard(static_cast<Edge>(e), ph, cl)) {
          ++holding;
          which = static_cast<Edge>(e);
        }
      }
      ASSERT_EQ(holding, 1) << "phase " << p << " class " << k;
      ASSERT_EQ(which, edge_for(ph, cl)) << "phase " << p << " class " << k;
      used.insert(edge_letter(which));
    }
  }
  // Every thesis letter A..L is an edge of the graph.
  for (char l = 'A'; l <= 'L'; ++l) {
    EXPECT_TRUE(used.count(l) == 1) << l;
  }
}

TEST(AxisTable, SelfLoopsAndEdges) {
  EXPECT_EQ(edge_target(Edge::A, Phase::Stop), Phase::Accel);
  EXPECT_EQ(edge_target(Edge::B, Phase::Accel), Phase::Const);
  EXPECT_EQ(edge_target(Edge::C, Phase::Const), Phase::Decel);
  EXPECT_EQ(edge_target(Edge::D, Phase::Accel), Phase::Decel);
  EXPECT_EQ(edge_target(Edge::E, Phase::Decel), Phase::Stop);
  EXPECT_EQ(edge_target(Edge::F, Phase::Decel), Phase::Accel);
  EXPECT_EQ(edge_target(Edge::I, Phase::Stop), Phase::Stop);
  EXPECT_EQ(edge_target(Edge::J, Phase::Accel), Phase::Accel);
  EXPECT_EQ(edge_target(Edge::K, Phase::Decel), Phase::Decel);
  EXPECT_EQ(edge_target(Edge::L, Phase::Const), Phase::Const);
}

namespace {
Config gen_config() {
  Config c;
  c.v_start = *rc::gen::inRange<int32_t>(1, 2000);
  c.v_slow = *rc::gen::inRange<int32_t>(c.v_start, 20000);
  c.v_fast = *rc::gen::inRange<int32_t>(c.v_slow, kSpeedMax + 1);
  c.accel = *rc::gen::inRange<int32_t>(1, kAccelMax + 1);
  c.soft_min = *rc::gen::inRange<int32_t>(-kPosMax, kPosMax - 1);
  c.soft_max = *rc::gen::inRange<int32_t>(c.soft_min + 1, kPosMax + 1);
  c.home_travel = *rc::gen::inRange<int32_t>(1, kPosMax + 1);
  c.home_position = *rc::gen::inRange<int32_t>(-kPosMax, kPosMax + 1);
  return c;
}

State gen_state(const Config& c) {
  State s;
  s.phase = static_cast<Phase>(*rc::gen::inRange<int>(0, 4));
  s.mode = static_cast<Mode>(*rc::gen::inRange<int>(0, 4));
  s.dir = *rc::gen::element<int8_t>(1, -1);
  s.jog_dir = *rc::gen::element<int8_t>(1, -1);
  s.level = *rc::gen::inRange<uint8_t>(0, 2);
  s.latch_min = *rc::gen::inRange<uint8_t>(0, 2);
  s.latch_max = *rc::gen::inRange<uint8_t>(0, 2);
  s.homed = *rc::gen::inRange<uint8_t>(0, 2);
  s.pos = *rc::gen::inRange<int32_t>(-kPosMax, kPosMax + 1);
  s.target = *rc::gen::inRange<int32_t>(-kPosMax, kPosMax + 1);
  s.v = s.phase == Phase::Stop ? 0 : *rc::gen::inRange<int32_t>(1, c.v_fast * kSpeedScale + 1);
  s.frac = *rc::gen::inRange<int32_t>(0, kDistScale);
  return s;
}

Input gen_input() {
  Input in;
  in.cmd.kind = static_cast<CmdKind>(*rc::gen::inRange<int>(0, 8));
  in.cmd.dir = *rc::gen::element<int8_t>(1, -1, 0, 5);
  in.cmd.level = *rc::gen::element<uint8_t>(0, 1, 2);
  in.cmd.value = *rc::gen::arbitrary<int32_t>();
  in.endstop_min = *rc::gen::element<uint8_t>(0, 0, 0, 1);
  in.endstop_max = *rc::gen::element<uint8_t>(0, 0, 0, 1);
  in.blocked = *rc::gen::element<uint8_t>(0, 0, 0, 1);
  in.link_alive = *rc::gen::element<uint8_t>(1, 1, 0);
  return in;
}
}  // namespace

// Over arbitrary valid (state, input, config): the class the step reports agrees with what
// happened to the speed, its edge is the table's, the result is valid and deterministic.
RC_GTEST_PROP(AxisTable, ClassMatchesEffect, ()) {
  const Config c = gen_config();
  const State s = gen_state(c);
  const Input in = gen_input();
  RC_PRE(state_valid(s));
  const StepResult r = step(s, in, c);
  const StepResult again = step(s, in, c);
  RC_ASSERT(r.state.pos == again.state.pos && r.out.steps == again.out.steps && r.state.v == again.state.v &&
            r.out.edge == again.out.edge && r.state.frac == again.state.frac);
  RC_ASSERT(state_valid(r.state));
  RC_ASSERT(r.out.edge == edge_for(s.phase, r.out.cls));
  RC_ASSERT(r.state.phase == edge_target(r.out.edge, s.phase));
  RC_ASSERT(r.out.steps >= 0 && r.out.steps <= 1001);
  const int32_t sf = c.v_start * kSpeedScale;
  switch (r.out.cls) {
    case Class::Faster:
      if (s.phase == Phase::Stop) {
        RC_ASSERT(r.state.v == sf);
        RC_ASSERT(r.out.steps == 0);  // DIR settles one tick before the first STEP
      } else {
        RC_ASSERT(r.state.v > s.v && r.state.v - s.v <= c.accel);
      }
      break;
    case Class::Same: RC_ASSERT(r.state.v == s.v); break;
    case Class::Slower: RC_ASSERT(r.state.v < s.v && s.v - r.state.v <= c.accel); break;
    default: RC_ASSERT(r.state.v == 0); break;
  }
  if (r.state.dir != s.dir) {
    RC_ASSERT(s.phase == Phase::Stop);
  }
}

TEST(AxisInvalid, BadConfigOrStateForcesStop) {
  Config bad;
  bad.accel = 0;
  State s = homed_at(0);
  s.phase = Phase::Const;
  s.v = 1'000'000;
  StepResult r = step(s, Input{}, bad);
  EXPECT_EQ(r.out.error, Error::BadConfig);
  EXPECT_EQ(r.state.phase, Phase::Stop);
  EXPECT_EQ(r.out.steps, 0);
  EXPECT_EQ(r.out.edge, Edge::X);
  State weird = s;
  weird.v = 0;  // moving phase with zero speed
  r = step(weird, Input{}, Config{});
  EXPECT_EQ(r.out.error, Error::BadState);
  EXPECT_TRUE(state_valid(r.state));
  weird = s;
  weird.phase = static_cast<Phase>(9);
  r = step(weird, Input{}, Config{});
  EXPECT_EQ(r.out.error, Error::BadState);
  EXPECT_TRUE(state_valid(r.state));
}

// ---- commands ---------------------------------------------------------------------------

// A rejected command reports a typed error and changes nothing: the tick is identical to a
// tick without that command.
RC_GTEST_PROP(AxisCommands, RejectedCommandChangesNothing, ()) {
  const Config c = gen_config();
  const State s = gen_state(c);
  RC_PRE(state_valid(s));
  const Input in = gen_input();
  const StepResult r = step(s, in, c);
  if (r.out.error != Error::None && r.out.error != Error::HomeFailed) {
    Input none = in;
    none.cmd = Command{};
    const StepResult base = step(s, none, c);
    RC_ASSERT(r.state.pos == base.state.pos);
    RC_ASSERT(r.state.target == base.state.target);
    RC_ASSERT(r.state.mode == base.state.mode);
    RC_ASSERT(r.state.v == base.state.v);
    RC_ASSERT(r.state.jog_dir == base.state.jog_dir);
    RC_ASSERT(r.state.level == base.state.level);
    RC_ASSERT(r.state.homed == base.state.homed);
    RC_ASSERT(r.out.steps == base.out.steps);
  }
}

TEST(AxisCommands, TypedErrors) {
  Config c;
  State s = homed_at(1000);
  EXPECT_EQ(step(s, Input{{CmdKind::MoveAbs, 0, 0, c.soft_max + 1}}, c).out.error, Error::OutOfLimits);
  EXPECT_EQ(step(s, Input{{CmdKind::MoveRel, 0, 0, -1001}}, c).out.error, Error::OutOfLimits);
  EXPECT_EQ(step(s, Input{{CmdKind::Jog, 0, 0, 0}}, c).out.error, Error::BadCommand);
  EXPECT_EQ(step(s, Input{{CmdKind::Jog, 1, 7, 0}}, c).out.error, Error::BadCommand);
  EXPECT_EQ(step(s, Input{{static_cast<CmdKind>(42), 1, 0, 0}}, c).out.error, Error::BadCommand);
  Input blocked{{CmdKind::MoveAbs, 0, 0, 5000}};
  blocked.blocked = 1;
  EXPECT_EQ(step(s, blocked, c).out.error, Error::Blocked);
  State unhomed = s;
  unhomed.homed = 0;
  EXPECT_EQ(step(unhomed, Input{{CmdKind::MoveAbs, 0, 0, 5000}}, c).out.error, Error::NotHomed);
  Input toward{{CmdKind::Jog, -1, 0, 0}};
  toward.endstop_min = 1;
  EXPECT_EQ(step(s, toward, c).out.error, Error::TowardEndstop);
}

TEST(AxisCommands, RelativeMoveIsFromCurrentPosition) {
  Config c;
  State s = homed_at(5000);
  const test::MoveResult r0 = test::run_move(s, c, 5000 + 1234, 1, 100000);
  State s2 = homed_at(5000);
  StepResult r = run(s2, c, Input{{CmdKind::MoveRel, 0, 1, 1234}}, 3000);
  EXPECT_EQ(r.state.pos, 6234);
  EXPECT_EQ(r0.final_pos, 6234);
  r = run(s2, c, Input{{CmdKind::MoveRel, 0, 1, -6000}}, 3000);
  EXPECT_EQ(r.state.pos, 234);
}

// ---- safety stops -----------------------------------------------------------------------

TEST(AxisEndstop, StopsAtOnceAndRefusesUntilLeft) {
  Config c;
  State s = homed_at(100'000);
  run(s, c, Input{{CmdKind::Jog, -1, 1, 0}}, 2500);
  ASSERT_EQ(s.phase, Phase::Const);
  Input hit;
  hit.endstop_min = 1;
  StepResult r = step(s, hit, c);
  EXPECT_EQ(r.out.edge, Edge::G);
  EXPECT_EQ(r.out.steps, 0);
  EXPECT_EQ(r.state.v, 0);
  s = r.state;
  // Still on the switch: refused toward it, allowed away.
  hit.cmd = Command{CmdKind::Jog, -1, 1, 0};
  EXPECT_EQ(step(s, hit, c).out.error, Error::TowardEndstop);
  // Switch released (bounce) but not yet moved away: still refused.
  Input released{{CmdKind::Jog, -1, 1, 0}};
  EXPECT_EQ(step(s, released, c).out.error, Error::TowardEndstop);
  const int32_t at = s.pos;
  run(s, c, Input{{CmdKind::Jog, 1, 0, 0}}, 50);
  EXPECT_GT(s.pos, at);
  EXPECT_EQ(s.latch_min, 0);
  EXPECT_EQ(step(s, released, c).out.error, Error::None);
  // The max endstop is the mirror image (H).
  State m = homed_at(100'000);
  run(m, c, Input{{CmdKind::Jog, 1, 1, 0}}, 500);
  Input hmax;
  hmax.endstop_max = 1;
  r = step(m, hmax, c);
  EXPECT_EQ(r.out.edge, Edge::H);
  EXPECT_EQ(r.out.steps, 0);
}

TEST(AxisBlocked, BrakesAndHolds) {
  Config c;
  State s = homed_at(100'000);
  run(s, c, Input{{CmdKind::Jog, 1, 1, 0}}, 2500);
  Input b;
  b.blocked = 1;
  int32_t prev = s.v;
  for (int t = 0; t < 5000; ++t) {
    const StepResult r = step(s, b, c);
    if (r.state.v != 0) {
      ASSERT_LE(prev - r.state.v, c.accel);
    }
    if (prev == 0) {
      ASSERT_EQ(r.out.steps, 0);
    }
    prev = r.state.v;
    s = r.state;
  }
  EXPECT_EQ(s.phase, Phase::Stop);
  // Unblocking does not resume the cleared jog (G16).
  run(s, c, Input{}, 100);
  EXPECT_EQ(s.phase, Phase::Stop);
}

TEST(AxisEStop, CutsAtOnce) {
  Config c;
  State s = homed_at(100'000);
  run(s, c, Input{{CmdKind::Jog, 1, 1, 0}}, 2500);
  const StepResult r = step(s, Input{{CmdKind::EStop, 0, 0, 0}}, c);
  EXPECT_EQ(r.out.edge, Edge::X);
  EXPECT_EQ(r.state.v, 0);
  EXPECT_EQ(r.out.steps, 0);
}

TEST(AxisHoming, FindsMinEndstopAndZeroes) {
  Config c;
  c.home_position = 0;
  State s;  // unhomed, counter 0, carriage really 5000 usteps above the switch
  const int32_t switch_at = -5000;
  Input in{{CmdKind::Home, 0, 0, 0}};
  for (int t = 0; t < 20000 && !(s.homed != 0 && s.phase == Phase::Stop); ++t) {
    in.endstop_min = s.pos <= switch_at ? 1 : 0;
    const StepResult r = step(s, in, c);
    ASSERT_LE(r.state.v, c.v_slow * kSpeedScale);
    s = r.state;
    in.cmd = Command{};
  }
  EXPECT_EQ(s.homed, 1);
  EXPECT_EQ(s.pos, 0);
  EXPECT_EQ(s.mode, Mode::Idle);
}

TEST(AxisHoming, FailsAfterHomeTravel) {
  Config c;
  c.home_travel = 3000;
  State s;
  StepResult r = step(s, Input{{CmdKind::Home, 0, 0, 0}}, c);
  s = r.state;
  bool failed = false;
  for (int t = 0; t < 20000 && !failed; ++t) {
    r = step(s, Input{}, c);
    s = r.state;
    failed = r.out.error == Error::HomeFailed;
  }
  EXPECT_TRUE(failed);
  EXPECT_EQ(s.pos, -3000);
  EXPECT_EQ(s.homed, 0);
}

TEST(AxisSoftLimits, JogStopsAtLimitWithoutCrossing) {
  Config c;
  State s = homed_at(c.soft_max - 20000);
  int32_t max_pos = s.pos;
  Input in{{CmdKind::Jog, 1, 1, 0}};
  for (int t = 0; t < 5000; ++t) {
    const StepResult r = step(s, in, c);
    s = r.state;
    max_pos = std::max(max_pos, s.pos);
    if (r.out.edge == Edge::E) {
      EXPECT_LE(r.out.step_speed, c.v_start * kSpeedScale);
    }
  }
  EXPECT_EQ(max_pos, c.soft_max);
  EXPECT_EQ(s.pos, c.soft_max);
  EXPECT_EQ(s.phase, Phase::Stop);
}

TEST(AxisDistance, DiscreteNeverExceedsContinuous) {
  // DD at the extremes of the documented ranges: no overflow, and within the continuous bound.
  for (int32_t a : {1, 7, 8000, kAccelMax}) {
    for (int32_t v : {kFineSpeedMax, kFineSpeedMax - 1, 123'456'789, 160'001}) {
      const int64_t d = stop_distance_fine(v, 160'000, a);
      const long double cont = (static_cast<long double>(v) * v - 160'000.0L * 160'000.0L) / (2.0L * a);
      ASSERT_GE(d, 0) << v << " " << a;
      ASSERT_LE(static_cast<long double>(d), cont) << v << " " << a;
      ASSERT_GE(static_cast<long double>(d), cont - static_cast<long double>(v)) << v << " " << a;
    }
  }
}

// Regression (found by AxisStateful): Home issued while jogging fast toward min with a homing
// travel shorter than the stopping distance used to stop at the homing bound at full speed.
TEST(AxisHoming, HomeWhileMovingFastBrakesPastTheBound) {
  Config c;
  c.home_travel = 1000;
  State s;  // unhomed
  run(s, c, Input{{CmdKind::Jog, -1, 1, 0}}, 2500);
  ASSERT_EQ(s.v, c.v_fast * kSpeedScale);
  Input in{{CmdKind::Home, 0, 0, 0}};
  bool failed = false;
  for (int t = 0; t < 5000 && !failed; ++t) {
    const StepResult r = step(s, in, c);
    in.cmd = Command{};
    if (r.state.v == 0 && s.v != 0) {
      ASSERT_LE(r.out.step_speed, c.v_start * kSpeedScale) << t;
      ASSERT_TRUE(s.v <= c.v_start * kSpeedScale || s.v - r.out.step_speed <= c.accel) << t;
    } else if (r.state.v != 0) {
      ASSERT_LE(std::abs(r.state.v - s.v), c.accel) << t;
    }
    failed = r.out.error == Error::HomeFailed;
    s = r.state;
  }
  EXPECT_TRUE(failed);
  EXPECT_EQ(s.phase, Phase::Stop);
}

// docs/motion.md "Homing and the encoder zero": the count programmed into the encoder at the
// home position gives that position back through eq. 7-2 at the next power-up, for every
// mechanics with at most REN = 16384 microsteps per turn; above it at most rev / 16384 more.
RC_GTEST_PROP(AxisEncoderZero, ProgrammedCountReadsBackTheHomePosition, ()) {
  const auto rev = *rc::gen::inRange<std::int32_t>(1, 256'001);
  const auto pos = *rc::gen::inRange<std::int32_t>(-1'000'000'000, 1'000'000'001);
  const std::int64_t c = ap::xy_axis::encoder_counts_for(pos, rev);
  const ap::xy_axis::StartPosition back = ap::xy_axis::encoder_to_usteps(ap::xy_axis::encoder_reading_at(c), rev);
  if (back.error != ap::xy_axis::Error::None) {
    // Only where eq. 7-2's result leaves the counter's range.
    RC_ASSERT(std::llabs(static_cast<long long>(pos)) + rev / 16384 + 1 > 1'000'000'000LL);
    return;
  }
  if (rev <= 16384) {
    RC_ASSERT(back.pos == pos);
  } else {
    RC_ASSERT(back.pos >= pos);
    RC_ASSERT(static_cast<std::int64_t>(back.pos) - pos <= rev / 16384);
  }
}

TEST(AxisEncoderZero, WorkedValues) {
  // 3200 usteps a turn (200 x 16): 16000 usteps = 5 turns = 81920 counts; -1600 = -8192.
  EXPECT_EQ(ap::xy_axis::encoder_counts_for(16000, 3200), 81920);
  EXPECT_EQ(ap::xy_axis::encoder_counts_for(-1600, 3200), -8192);
  EXPECT_EQ(ap::xy_axis::encoder_counts_for(0, 3200), 0);
  const ap::xy_axis::EncoderReading r = ap::xy_axis::encoder_reading_at(-8192);
  EXPECT_EQ(r.turns, -1);
  EXPECT_EQ(r.counts, 8192);
}
