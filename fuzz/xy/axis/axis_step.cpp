// core/xy/axis step() driven directly by a fuzz-decoded script, with the motion safety
// properties (docs/motion.md) asserted after every tick; any violation aborts.
//
// Input: byte 0 flags (bit 0: raw config, any bit pattern; bit 1: raw start state; bit 2:
// start homed), then the config (raw: 8 x int32; else 10 bytes scaled into the documented
// ranges, small values so a move ends within a few thousand ticks), then ops, one byte each
// (low 3 bits = op) plus arguments:
//   0  command: kind byte (CmdKind 0..6, or any value), dir byte, level byte, value (4 bytes,
//      scaled into the soft limits +-1 % unless the kind byte's bit 7 is set), then one tick
//   1  endstop min = bit 3 of the op, max = bit 4
//   2  blocked = bit 3
//   3  link alive = bit 3
//   4  ticks: (n + 1) * 8, no command
//   5  ticks until the axis stands (at most 4000)
//   6  units: um/speed/accel conversions and start position on the fuzz bytes (totality)
//   7  one tick with the same input as the last one
// Invalid config or start state: every tick must force Stop with BadConfig / BadState.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/xy/axis/axis.hpp"
#include "core/xy/axis/position.hpp"
#include "core/xy/axis/step_timer.hpp"
#include "core/xy/axis/units.hpp"
#include "fuzz/script_reader.hpp"

namespace {

using namespace ap::xy_axis;

constexpr std::int64_t kMaxTicks = 20'000;

[[noreturn]] void violation(const char* what, std::int64_t tick) {
  std::fprintf(stderr, "axis_step fuzz: safety property violated: %s (tick %lld)\n", what, static_cast<long long>(tick));
  std::abort();
}

using ap::fuzz::Reader;

Config scaled_config(Reader& r) {
  Config c;
  c.v_start = 1 + r.u8() * 8;                                   // 1 .. 2041 usteps/s
  c.v_slow = c.v_start + r.u16() % 20'000;
  c.v_fast = std::min<std::int32_t>(kSpeedMax, c.v_slow + static_cast<std::int32_t>(r.u16()) * 16);
  c.accel = 1 + static_cast<std::int32_t>(r.u16()) * 32;        // up to ~2.1e6 usteps/s^2
  const std::int32_t span = 1 + static_cast<std::int32_t>(r.u16()) * 4;
  c.soft_min = -static_cast<std::int32_t>(r.u8()) * 64;
  c.soft_max = c.soft_min + span;
  c.home_travel = std::clamp<std::int32_t>(2 * span, 1, kPosMax);
  c.home_position = c.soft_min + static_cast<std::int32_t>(r.u8() % 4) * (span / 4);
  return c;
}

Config raw_config(Reader& r) {
  Config c;
  c.v_start = r.i32();
  c.v_slow = r.i32();
  c.v_fast = r.i32();
  c.accel = r.i32();
  c.soft_min = r.i32();
  c.soft_max = r.i32();
  c.home_travel = r.i32();
  c.home_position = r.i32();
  return c;
}

State raw_state(Reader& r) {
  State s;
  s.phase = static_cast<Phase>(r.u8() % 5);
  s.mode = static_cast<Mode>(r.u8() % 5);
  s.dir = static_cast<std::int8_t>(r.u8());
  s.jog_dir = static_cast<std::int8_t>(r.u8());
  s.level = r.u8() % 3;
  s.latch_min = r.u8() % 3;
  s.latch_max = r.u8() % 3;
  s.homed = r.u8() % 3;
  s.pos = r.i32();
  s.target = r.i32();
  s.v = r.i32();
  s.frac = r.i32();
  return s;
}

struct Harness {
  Config cfg;
  State s;
  Input in;
  bool valid = false;  // config and start state valid: the safety properties apply
  std::int64_t ticks = 0;
  bool latch_min = false;
  bool latch_max = false;
  bool blocked_stopped = false;
  bool tracking = false;
  std::int32_t target = 0;
  int side = 0;

  void tick(const Command& cmd) {
    if (ticks >= kMaxTicks) return;
    ++ticks;
    in.cmd = cmd;
    const State p = s;
    const StepResult r = step(p, in, cfg);
    s = r.state;
    const Output& o = r.out;
    if (!valid) {
      // Totality: a bad config or state stops the axis, reported, and emits nothing.
      if (o.steps != 0 || s.phase != Phase::Stop || s.v != 0) violation("invalid config/state did not force Stop", ticks);
      if (o.error != Error::BadConfig && o.error != Error::BadState) violation("invalid config/state not reported", ticks);
      valid = config_valid(cfg) && state_valid(s);
      return;
    }
    const std::int32_t sf = cfg.v_start * kSpeedScale;
    if (!state_valid(s)) violation("state out of its invariant ranges", ticks);
    if (o.steps < 0 || o.steps > kSpeedMax / kTicksPerSecond) violation("steps per tick out of range", ticks);
    // (A raw start state may already be faster: then it may only brake.)
    if (s.v > p.v && s.v > std::max(cfg.v_fast, cfg.v_start) * kSpeedScale) violation("accelerated above the fast speed", ticks);
    if (s.dir != p.dir && p.v > sf) violation("DIR flipped above the start speed", ticks);
    if (o.steps > 0 && o.dir != s.dir) violation("steps emitted against the DIR state", ticks);
    if (in.endstop_min != 0) latch_min = true;
    if (in.endstop_max != 0) latch_max = true;
    if (o.steps > 0) {
      if (o.dir < 0 && latch_min) violation("step toward an active min endstop", ticks);
      if (o.dir > 0 && latch_max) violation("step toward an active max endstop", ticks);
      if (o.dir > 0 && in.endstop_min == 0) latch_min = false;
      if (o.dir < 0 && in.endstop_max == 0) latch_max = false;
    }
    if (in.blocked != 0) {
      if (s.v > p.v) violation("speed increased while blocked", ticks);
      if (blocked_stopped && (o.steps != 0 || s.v != 0)) violation("step while blocked after the stop", ticks);
      blocked_stopped = blocked_stopped || s.v == 0;
    } else {
      blocked_stopped = false;
    }
    // The step counter moves by exactly the steps emitted, except where homing sets it: the
    // first reference, a Home command, or a homing that ends on the min switch (edge G, or
    // edge I standing on it: docs/motion.md §6, G19) in a start state that was already homed.
    const bool rehomed = p.mode == Mode::Home && s.homed != 0 && s.pos == cfg.home_position &&
                         (in.endstop_min != 0 || p.latch_min != 0);
    const bool homing_reset = (s.homed != 0 && p.homed == 0) || cmd.kind == CmdKind::Home || rehomed;
    if (!homing_reset && static_cast<std::int64_t>(s.pos) - p.pos != static_cast<std::int64_t>(o.dir) * o.steps) {
      violation("position moved by other than the steps emitted", ticks);
    }
    if (p.homed != 0 && s.homed != 0 && p.pos >= cfg.soft_min && p.pos <= cfg.soft_max &&
        (s.pos < cfg.soft_min || s.pos > cfg.soft_max)) {
      violation("soft travel limit crossed", ticks);
    }
    if (in.link_alive == 0 && p.mode != Mode::Jog && s.mode == Mode::Jog) violation("jog started with the link dead", ticks);
    // A new command, a block (a braking stop may pass the target) or a homing re-reference
    // ends the move that was being tracked.
    if (cmd.kind != CmdKind::None || in.blocked != 0 || homing_reset) tracking = false;
    const bool new_move = s.mode == Mode::Position && (p.mode != Mode::Position || p.target != s.target);
    if (new_move) {
      tracking = p.v == 0 && in.blocked == 0;
      target = s.target;
      side = p.pos > s.target ? 1 : (p.pos < s.target ? -1 : 0);
    }
    if (tracking) {
      const int now = s.pos > target ? 1 : (s.pos < target ? -1 : 0);
      if (now != 0 && side != 0 && now != side) violation("reachable target passed", ticks);
      if (now != 0) side = now;
      if (s.mode != Mode::Position || s.target != target) tracking = false;
    }
  }

  Command command(Reader& r) const {
    Command c;
    const std::uint8_t k = r.u8();
    c.kind = static_cast<CmdKind>((k & 0x80U) != 0 ? k & 0x7FU : k % 7);
    const std::uint8_t d = r.u8();
    c.dir = (d & 0x80U) != 0 ? static_cast<std::int8_t>(d) : ((d & 1U) != 0 ? std::int8_t{1} : std::int8_t{-1});
    const std::uint8_t l = r.u8();
    c.level = (l & 0x80U) != 0 ? l : static_cast<std::uint8_t>(l & 1U);
    const std::int32_t raw = r.i32();
    if ((k & 0x80U) != 0) {
      c.value = raw;
    } else {
      const std::int64_t span = static_cast<std::int64_t>(cfg.soft_max) - cfg.soft_min;
      const std::int64_t lo = static_cast<std::int64_t>(cfg.soft_min) - span / 100 - 1;
      const std::int64_t v = lo + static_cast<std::int64_t>(static_cast<std::uint32_t>(raw) % static_cast<std::uint64_t>(std::max<std::int64_t>(1, span + span / 50 + 3)));
      const std::int64_t value = c.kind == CmdKind::MoveRel ? v - s.pos : v;
      c.value = static_cast<std::int32_t>(std::clamp<std::int64_t>(value, INT32_MIN, INT32_MAX));
    }
    return c;
  }

  static void units(Reader& r) {
    const Mechanics m{r.i32() % 100'000, static_cast<std::int32_t>(r.u16()), static_cast<std::int32_t>(1U << (r.u8() % 10))};
    const std::int32_t a = r.i32();
    const std::int32_t b = r.i32();
    if (!mechanics_valid(m)) return;
    const Converted u = um_to_usteps(a, m, static_cast<Round>(r.u8() % 3));
    if (u.error == Error::None && (u.value < -kPosMax || u.value > kPosMax)) violation("um_to_usteps out of range", 0);
    (void)speed_to_usteps(a, m);
    (void)accel_to_usteps(b, m);
    const UstepLimits lim = limits_to_usteps(std::min(a, b), std::max(a, b), m);
    if (lim.error == Error::None && lim.min > lim.max) violation("limits out of order", 0);
    const Converted t = target_to_usteps(a, std::min(a, b), std::max(a, b), m);
    if (t.error == Error::None && lim.error == Error::None && (t.value < lim.min || t.value > lim.max)) {
      violation("target outside its converted limits", 0);
    }
    (void)usteps_to_um(a, m);
    const auto rev = static_cast<std::int32_t>(usteps_per_rev(m));
    const EncoderReading e{static_cast<std::int8_t>(b), static_cast<std::uint16_t>(b >> 8), static_cast<std::uint8_t>(b >> 24)};
    const StartPosition sp = start_position(&e, {a, static_cast<std::uint8_t>(b & 1)}, rev);
    if (sp.error == Error::None && !state_valid(initial_state(sp))) violation("start position gives an invalid state", 0);
    if (const auto ts = step_timer(static_cast<std::uint32_t>(a))) (void)step_ccr(*ts);
    // The transition table (Tab. 7-3 + gaps): exactly one edge per (phase, class), and the
    // names used by reports. Out-of-range enum values must be answered, not trusted.
    const auto ph = static_cast<Phase>(static_cast<std::uint8_t>(b) % (kPhaseCount + 1));
    const auto cl = static_cast<Class>(static_cast<std::uint8_t>(b >> 8) % (kClassCount + 1));
    const Edge edge = edge_for(ph, cl);
    if (static_cast<int>(ph) < kPhaseCount && static_cast<int>(cl) < kClassCount) {
      int guards = 0;
      for (int k = 0; k < kEdgeCount; ++k) guards += edge_guard(static_cast<Edge>(k), ph, cl) ? 1 : 0;
      if (guards != 1 || !edge_guard(edge, ph, cl)) violation("transition table not total and deterministic", 0);
      if (static_cast<int>(edge_target(edge, ph)) >= kPhaseCount) violation("edge leads outside the phases", 0);
    }
    (void)edge_letter(static_cast<Edge>(static_cast<std::uint8_t>(b >> 16) % (kEdgeCount + 1)));
    (void)phase_name(ph);
    (void)mode_name(static_cast<Mode>(static_cast<std::uint8_t>(b >> 24) % 5));
  }

  void run(const std::uint8_t* data, std::size_t size) {
    Reader r{data, size};
    const std::uint8_t flags = r.u8();
    cfg = (flags & 1U) != 0 ? raw_config(r) : scaled_config(r);
    if ((flags & 2U) != 0) {
      s = raw_state(r);
    } else {
      s = State{};
      s.homed = (flags & 4U) != 0 ? 1 : 0;
      s.pos = static_cast<std::int32_t>((static_cast<std::int64_t>(cfg.soft_min) + cfg.soft_max) / 2);
      s.target = s.pos;
    }
    valid = config_valid(cfg) && state_valid(s);
    latch_min = s.latch_min != 0;
    latch_max = s.latch_max != 0;
    Command last{};
    while (r.more() && ticks < kMaxTicks) {
      const std::uint8_t op = r.u8();
      switch (op & 7U) {
        case 0: last = command(r); tick(last); break;
        case 1:
          in.endstop_min = (op >> 3) & 1U;
          in.endstop_max = (op >> 4) & 1U;
          break;
        case 2: in.blocked = (op >> 3) & 1U; break;
        case 3: in.link_alive = (op >> 3) & 1U; break;
        case 4: {
          const int n = (r.u8() + 1) * 8;
          for (int i = 0; i < n; ++i) tick({});
          break;
        }
        case 5:
          for (int i = 0; i < 4000 && (s.phase != Phase::Stop || i == 0); ++i) tick({});
          break;
        case 6: units(r); break;
        default: tick(last); break;
      }
    }
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Harness h;
  h.run(data, size);
  return 0;
}
