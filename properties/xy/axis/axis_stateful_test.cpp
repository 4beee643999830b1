// RapidCheck stateful test (rc::state): two axes driven by random command sequences at
// random ticks, the way the PC and the board supervisor will drive them: jog held by repeats
// every 100 ms, reversals, absolute/relative moves, retargets ahead-too-close and behind the
// carriage, stop, emergency stop, endstop events, block/unblock, link loss (watchdog).
// After every tick, every axis is checked against the requirements of docs/motion.md (Rig::check).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>
#include <rapidcheck/state.h>

#include <array>
#include <cmath>
#include <optional>

#include "axis_harness.hpp"
#include "core/xy/axis/axis.hpp"
#include "core/xy/axis/watchdog.hpp"
#include "models/xy/motion/ideal.hpp"

using namespace ap::xy_axis;
namespace model = ap::model::xy_motion;

namespace {

constexpr int64_t kSlackTicks = 3;  // same documented bound as axis_model

struct Model {
  std::array<Config, 2> cfg{};
};

struct TrackedMove {
  int32_t target = 0;
  bool far = false;        // set at least the (continuous) stopping distance ahead, or from rest
  int passes = 0;          // times the carriage crossed the target
  int last_side = 0;       // sign(pos - target) when last nonzero
  int64_t t0 = 0;
  bool from_rest = false;
  bool clean = true;       // nothing else touched the axis since the command
  double t_ref = 0;
};

struct AxisRig {
  Config c{};
  State s{};
  bool latch_min = false;  // checker's own memory: endstop seen, not yet moved away
  bool latch_max = false;
  bool blocked_stopped = false;
  std::optional<TrackedMove> move;
  std::optional<Command> pending;
  Command repeat{};        // what the PC repeats every 100 ms while a key is held
  bool jogging_request = false;
  std::array<uint8_t, 2> endstop{};  // min, max
  int64_t moves_arrived = 0;
  int64_t idle_ticks = 0;
  int64_t overrun_returned = 0;
  int64_t endstop_stops = 0;
  int64_t reversals = 0;
};

struct Rig {
  std::array<AxisRig, 2> ax{};
  LinkWatchdog wd{};
  int64_t t = 0;
  bool blocked = false;
  bool link_up = true;
  int64_t silent = 0;
  int64_t link_timeouts = 0;

  void tick_n(int n) {
    for (int i = 0; i < n; ++i) {
      tick();
    }
  }

  void tick() {
    ++t;
    bool sent = false;
    std::array<Command, 2> cmd{};
    if (link_up) {
      for (size_t a = 0; a < 2; ++a) {
        if (ax[a].pending) {
          cmd[a] = *ax[a].pending;
          sent = true;
        } else if (t % kCommandPeriodTicks == 0) {
          cmd[a] = ax[a].repeat;  // a held jog, or DummyData (None) as a keep-alive
          sent = true;
        }
      }
    }
    for (auto& x : ax) {
      x.pending.reset();
    }
    wd = watchdog_tick(wd, sent);
    silent = sent ? 0 : silent + 1;
    for (size_t a = 0; a < 2; ++a) {
      Input in;
      in.cmd = cmd[a];
      in.endstop_min = ax[a].endstop[0];
      in.endstop_max = ax[a].endstop[1];
      in.blocked = blocked ? 1 : 0;
      in.link_alive = link_alive(wd) ? 1 : 0;
      const State before = ax[a].s;
      const StepResult r = step(before, in, ax[a].c);
      check(ax[a], before, in, r);
      ax[a].s = r.state;
    }
  }

  void check(AxisRig& x, const State& p, const Input& in, const StepResult& r) {
    const Config& c = x.c;
    const State& n = r.state;
    const Output& o = r.out;
    const int32_t sf = c.v_start * kSpeedScale;
    RC_ASSERT(state_valid(n));
    // Speed never above the fast level.
    RC_ASSERT(n.v <= c.v_fast * kSpeedScale);
    RC_ASSERT(o.step_speed <= c.v_fast * kSpeedScale);
    // |dv| <= a per tick, except the 0 <-> start-speed jumps and the immediate stops.
    const bool immediate = o.edge == Edge::G || o.edge == Edge::H || o.edge == Edge::X;
    if (p.v == 0) {
      RC_ASSERT(n.v == 0 || n.v == sf);
    } else if (n.v == 0) {
      if (!immediate) {
        RC_ASSERT(o.edge == Edge::E);
        RC_ASSERT(o.step_speed <= sf);
        RC_ASSERT(p.v <= sf || (o.step_speed > 0 && p.v - o.step_speed <= c.accel));
      }
    } else {
      RC_ASSERT(std::abs(n.v - p.v) <= c.accel);
    }
    // DIR changes only from standstill (speed <= start speed).
    if (n.dir != p.dir) {
      RC_ASSERT(p.v == 0);
    }
    // No step toward an active endstop, nor toward one not yet moved away from.
    if (in.endstop_min != 0) x.latch_min = true;
    if (in.endstop_max != 0) x.latch_max = true;
    if (o.steps > 0) {
      RC_ASSERT(!(o.dir < 0 && x.latch_min));
      RC_ASSERT(!(o.dir > 0 && x.latch_max));
      if (o.dir > 0 && in.endstop_min == 0) x.latch_min = false;
      if (o.dir < 0 && in.endstop_max == 0) x.latch_max = false;
    }
    // Blocked: brakes (never speeds up), and once stopped no step until unblocked.
    if (in.blocked != 0) {
      RC_ASSERT(n.v <= p.v);
      if (x.blocked_stopped) {
        RC_ASSERT(o.steps == 0 && n.v == 0);
      }
      x.blocked_stopped = x.blocked_stopped || n.v == 0;
    } else {
      x.blocked_stopped = false;
    }
    // Soft limits are never crossed once the position is known.
    if (p.homed != 0 && n.homed != 0 && p.pos >= c.soft_min && p.pos <= c.soft_max) {
      RC_ASSERT(n.pos >= c.soft_min && n.pos <= c.soft_max);
    }
    // A jog does not outlive the link: the watchdog ends it and the axis brakes to a stop.
    if (silent >= kLinkTimeoutTicks) {
      RC_ASSERT(n.mode != Mode::Jog);
    }
    // Idle (released, stopped, blocked, link lost) means braking at <= a per tick: it ends
    // within the braking time from the top speed.
    const int64_t brake_ticks = (static_cast<int64_t>(c.v_fast) * kSpeedScale + c.accel - 1) / c.accel + 2;
    x.idle_ticks = n.mode == Mode::Idle ? x.idle_ticks + 1 : 0;
    if (x.idle_ticks > brake_ticks) {
      RC_ASSERT(n.v == 0);
    }
    if (o.edge == Edge::G || o.edge == Edge::H) ++x.endstop_stops;
    if (n.dir != p.dir) ++x.reversals;
    if (silent == kLinkTimeoutTicks) ++link_timeouts;
    track_move(x, p, in, r);
  }

  void track_move(AxisRig& x, const State& p, const Input& in, const StepResult& r) {
    const Config& c = x.c;
    const State& n = r.state;
    const int32_t sf = c.v_start * kSpeedScale;
    const bool new_move = (in.cmd.kind == CmdKind::MoveAbs || in.cmd.kind == CmdKind::MoveRel) &&
                          r.out.error == Error::None && n.mode == Mode::Position;
    if (x.move && (in.cmd.kind != CmdKind::None || in.blocked != 0 || in.endstop_min != 0 || in.endstop_max != 0)) {
      x.move->clean = false;
    }
    if (new_move) {
      TrackedMove m;
      m.target = n.target;
      m.t0 = t;
      m.from_rest = p.v == 0;
      const int64_t to_target = static_cast<int64_t>(m.target) - p.pos;
      const int64_t v_next = std::min<int64_t>(static_cast<int64_t>(p.v) + c.accel, static_cast<int64_t>(c.v_fast) * kSpeedScale);
      const int64_t need = test::continuous_brake_usteps(static_cast<int32_t>(v_next), c) + 2 * (v_next / test::kFine + 1) + 2;
      m.far = m.from_rest || (to_target * p.dir > 0 && std::llabs(to_target) >= need);
      m.last_side = to_target > 0 ? -1 : (to_target < 0 ? 1 : 0);
      if (m.from_rest) {
        const int32_t v_req = n.level != 0 ? c.v_fast : c.v_slow;
        m.t_ref = model::ideal_move(static_cast<double>(std::llabs(to_target)), c.v_start, v_req, c.accel).t_total;
      }
      x.move = m;
    }
    if (!x.move) {
      return;
    }
    TrackedMove& m = *x.move;
    const bool arrived = r.out.edge == Edge::E && n.pos == m.target && n.mode == Mode::Idle;
    if (!arrived && n.mode != Mode::Position) {
      // A stop, e-stop, block, endstop or link loss ended the move this tick: the axis brakes
      // as Idle and may roll past the old target, which is no longer a goal (found by this
      // test: a Stop one step before the target at just above the start speed).
      x.move.reset();
      return;
    }
    const int side = n.pos > m.target ? 1 : (n.pos < m.target ? -1 : 0);
    if (side != 0) {
      if (m.last_side != 0 && side != m.last_side) {
        ++m.passes;
      }
      m.last_side = side;
    } else if (!arrived && n.mode == Mode::Position && n.v > 0 && n.phase != Phase::Stop) {
      // On the target but still moving on: it will come out on the far side.
      RC_ASSERT(!m.far);
    }
    // Never past a target set at least the stopping distance ahead; a closer one (or one
    // behind the carriage) is overrun at most once and then reached from the other side.
    RC_ASSERT(m.passes <= (m.far ? 0 : 1));
    if (arrived) {
      RC_ASSERT(r.out.step_speed <= sf || r.out.steps == 0);
      if (m.from_rest && m.clean) {
        const double dur = static_cast<double>(t - m.t0 + 1) / kTicksPerSecond;
        RC_ASSERT(dur <= m.t_ref + static_cast<double>(kSlackTicks) / kTicksPerSecond + 1e-9);
      }
      ++x.moves_arrived;
      if (m.passes > 0) ++x.overrun_returned;
      x.move.reset();
    } else if (n.mode != Mode::Position || n.target != m.target) {
      x.move.reset();  // interrupted: stop, e-stop, block, endstop or a new command
    }
  }
};

using Cmd = rc::state::Command<Model, Rig>;

struct AxisArg {
  size_t a = *rc::gen::inRange<size_t>(0, 2);
  int after = *rc::gen::oneOf(rc::gen::inRange(0, 20), rc::gen::inRange(0, 20), rc::gen::inRange(0, 250), rc::gen::just(700));
};

struct Jog : Cmd {
  AxisArg k;
  int8_t dir = *rc::gen::element<int8_t>(1, -1);
  uint8_t level = *rc::gen::inRange<uint8_t>(0, 2);
  void run(const Model&, Rig& rig) const override {
    const ap::xy_axis::Command c{CmdKind::Jog, dir, level, 0};
    rig.ax[k.a].pending = c;
    rig.ax[k.a].repeat = c;
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override {
    os << "Jog(" << k.a << ", dir " << int{dir} << ", level " << int{level} << ") then " << k.after << " ticks";
  }
};

struct Release : Cmd {
  AxisArg k;
  void run(const Model&, Rig& rig) const override {
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::Stop, 0, 0, 0};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override { os << "Stop(" << k.a << ") then " << k.after << " ticks"; }
};

struct EStop : Cmd {
  AxisArg k;
  void run(const Model&, Rig& rig) const override {
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::EStop, 0, 0, 0};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override { os << "EStop(" << k.a << ") then " << k.after << " ticks"; }
};

struct MoveAbs : Cmd {
  AxisArg k;
  int64_t frac_permille = *rc::gen::inRange<int64_t>(-20, 1021);  // a little outside the limits too
  uint8_t level = *rc::gen::inRange<uint8_t>(0, 2);
  void run(const Model& m, Rig& rig) const override {
    const Config& c = m.cfg[k.a];
    const int64_t span = static_cast<int64_t>(c.soft_max) - c.soft_min;
    const int64_t t = c.soft_min + span * frac_permille / 1000;
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::MoveAbs, 0, level, static_cast<int32_t>(t)};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override {
    os << "MoveAbs(" << k.a << ", " << frac_permille << " permille, level " << int{level} << ") then " << k.after << " ticks";
  }
};

struct MoveRel : Cmd {
  AxisArg k;
  int32_t delta = *rc::gen::inRange<int32_t>(-20000, 20001);
  void run(const Model&, Rig& rig) const override {
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::MoveRel, 0, 1, delta};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override { os << "MoveRel(" << k.a << ", " << delta << ") then " << k.after << " ticks"; }
};

// Retarget relative to the moving carriage: behind it, or ahead but closer than it can stop.
struct Retarget : Cmd {
  AxisArg k;
  int32_t offset = *rc::gen::oneOf(rc::gen::inRange<int32_t>(-30000, 1), rc::gen::inRange<int32_t>(0, 400),
                                   rc::gen::inRange<int32_t>(0, 30000));
  void run(const Model& m, Rig& rig) const override {
    const Config& c = m.cfg[k.a];
    const State& s = rig.ax[k.a].s;
    const int64_t t = std::clamp<int64_t>(static_cast<int64_t>(s.pos) + static_cast<int64_t>(s.dir) * offset, c.soft_min,
                                          c.soft_max);
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::MoveAbs, 0, 1, static_cast<int32_t>(t)};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override { os << "Retarget(" << k.a << ", " << offset << " along DIR) then " << k.after << " ticks"; }
};

// Jog up to speed, then set a target just ahead, closer than the stopping distance: the axis
// must overrun it once, reverse, and come back to it from the other side.
struct JogThenCloseTarget : Cmd {
  AxisArg k;
  int8_t dir = *rc::gen::element<int8_t>(1, -1);
  int run_up = *rc::gen::inRange(50, 600);
  int32_t ahead = *rc::gen::inRange<int32_t>(0, 300);
  void run(const Model& m, Rig& rig) const override {
    const Config& c = m.cfg[k.a];
    const ap::xy_axis::Command jog{CmdKind::Jog, dir, 1, 0};
    rig.ax[k.a].pending = jog;
    rig.ax[k.a].repeat = jog;
    rig.tick_n(run_up);
    const State& s = rig.ax[k.a].s;
    const int64_t t = std::clamp<int64_t>(static_cast<int64_t>(s.pos) + static_cast<int64_t>(s.dir) * ahead, c.soft_min,
                                          c.soft_max);
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::MoveAbs, 0, 1, static_cast<int32_t>(t)};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after + 300);
  }
  void show(std::ostream& os) const override {
    os << "JogThenCloseTarget(" << k.a << ", dir " << int{dir} << ", " << run_up << " ticks, " << ahead << " ahead) then "
       << k.after + 300 << " ticks";
  }
};

struct Home : Cmd {
  AxisArg k;
  void run(const Model&, Rig& rig) const override {
    rig.ax[k.a].pending = ap::xy_axis::Command{CmdKind::Home, 0, 0, 0};
    rig.ax[k.a].repeat = ap::xy_axis::Command{};
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override { os << "Home(" << k.a << ") then " << k.after << " ticks"; }
};

struct Endstop : Cmd {
  AxisArg k;
  size_t which = *rc::gen::inRange<size_t>(0, 2);
  uint8_t on = *rc::gen::inRange<uint8_t>(0, 2);
  void run(const Model&, Rig& rig) const override {
    rig.ax[k.a].endstop[which] = on;
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override {
    os << "Endstop(" << k.a << ", " << (which == 0 ? "min" : "max") << ", " << int{on} << ") then " << k.after << " ticks";
  }
};

// The carriage reaches the switch it is heading for (or the min one when standing still).
struct EndstopHit : Cmd {
  AxisArg k;
  void run(const Model&, Rig& rig) const override {
    rig.ax[k.a].endstop[rig.ax[k.a].s.dir > 0 ? 1 : 0] = 1;
    rig.tick_n(k.after);
  }
  void show(std::ostream& os) const override { os << "EndstopHit(" << k.a << ") then " << k.after << " ticks"; }
};

struct Wait : Cmd {
  int after = *rc::gen::inRange(300, 1500);
  void run(const Model&, Rig& rig) const override { rig.tick_n(after); }
  void show(std::ostream& os) const override { os << "Wait " << after << " ticks"; }
};

struct Block : Cmd {
  bool on = *rc::gen::arbitrary<bool>();
  int after = *rc::gen::inRange(0, 250);
  void run(const Model&, Rig& rig) const override {
    rig.blocked = on;
    rig.tick_n(after);
  }
  void show(std::ostream& os) const override { os << "Block(" << on << ") then " << after << " ticks"; }
};

struct Link : Cmd {
  bool up = *rc::gen::arbitrary<bool>();
  int after = *rc::gen::oneOf(rc::gen::inRange(0, 250), rc::gen::just(900));
  void run(const Model&, Rig& rig) const override {
    rig.link_up = up;
    rig.tick_n(after);
  }
  void show(std::ostream& os) const override { os << "Link(" << (up ? "up" : "down") << ") then " << after << " ticks"; }
};

Config gen_axis_config() {
  Config c;
  c.v_start = *rc::gen::inRange<int32_t>(1, 3000);
  c.v_slow = *rc::gen::inRange<int32_t>(c.v_start, c.v_start + 10000);
  c.v_fast = *rc::gen::oneOf(rc::gen::inRange<int32_t>(c.v_slow + 5000, c.v_slow + 60000),
                             rc::gen::inRange<int32_t>(std::max(c.v_slow, 300'000), kSpeedMax + 1));
  c.accel = *rc::gen::oneOf(rc::gen::inRange<int32_t>(2000, 100000), rc::gen::inRange<int32_t>(100000, kAccelMax + 1));
  c.soft_min = *rc::gen::inRange<int32_t>(-50000, 50000);
  c.soft_max = c.soft_min + *rc::gen::inRange<int32_t>(2000, 60000);
  c.home_travel = *rc::gen::inRange<int32_t>(1000, 30000);
  c.home_position = c.soft_min;
  return c;
}

}  // namespace

RC_GTEST_PROP(AxisStateful, TwoAxesRandomCommands, ()) {
  Model m;
  m.cfg[0] = gen_axis_config();
  m.cfg[1] = gen_axis_config();
  Rig rig;
  for (size_t a = 0; a < 2; ++a) {
    rig.ax[a].c = m.cfg[a];
    const Config& c = m.cfg[a];
    rig.ax[a].s.homed = 1;
    rig.ax[a].s.pos = *rc::gen::inRange<int32_t>(c.soft_min, c.soft_max + 1);
    rig.ax[a].s.target = rig.ax[a].s.pos;
  }
  // rc::state::check with the sequence length scaled down: each command runs up to hundreds
  // of ticks, so shorter sequences keep a case cheap under sanitizers without losing variety.
  const auto cmds = *rc::gen::scale(
      0.4, rc::state::gen::commands(m, rc::state::gen::execOneOfWithArgs<Jog, Jog, Release, EStop, MoveAbs, MoveAbs, MoveRel,
                                                                          Retarget, Retarget, JogThenCloseTarget, Home, Endstop, EndstopHit, Block, Link, Wait>()));
  rc::state::runAll(cmds, m, rig);
  const auto sum = [&](int64_t AxisRig::*f) { return rig.ax[0].*f + rig.ax[1].*f; };
  RC_CLASSIFY(sum(&AxisRig::moves_arrived) > 0, "move arrived");
  RC_CLASSIFY(sum(&AxisRig::overrun_returned) > 0, "overrun, returned");
  RC_CLASSIFY(sum(&AxisRig::endstop_stops) > 0, "endstop stop");
  RC_CLASSIFY(sum(&AxisRig::reversals) > 0, "DIR reversal");
  RC_CLASSIFY(rig.link_timeouts > 0, "link timeout");
}
