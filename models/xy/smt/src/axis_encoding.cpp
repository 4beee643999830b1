// MIRRORS core/xy/axis/src/axis.cpp and table.cpp; see include/models/xy/smt/axis_encoding.hpp. Change together.
// One file, longer than the others: it is the encoding of one straight-line function, step()
// with its transition table, written in the same order as the C++ so the two can be read side
// by side (and the conformance property holds them together).
#include "models/xy/smt/axis_encoding.hpp"

#include <array>
#include <limits>

#include "core/xy/axis/watchdog.hpp"

namespace ap::model::smt::xy_axis {
namespace {

z3::expr zx(const z3::expr& e) { return z3::zext(e, 32); }

// Enum values (core/xy/axis/axis.hpp).
enum : int {
  kStop = 0, kAccel = 1, kConst = 2, kDecel = 3,
  kIdle = 0, kJog = 1, kPosition = 2, kHome = 3,
  cEStop = 0, cEndMin = 1, cEndMax = 2, cHalt = 3, cFaster = 4, cSame = 5, cSlower = 6,
  kNone = 0, kCmdJog = 1, kCmdStop = 2, kMoveAbs = 3, kMoveRel = 4, kCmdHome = 5, kCmdEStop = 6,
  eNone = 0, eBadCommand = 1, eOutOfLimits = 2, eBlocked = 3, eTowardEndstop = 4, eNotHomed = 5,
  eHomeFailed = 6, eBadConfig = 7, eBadState = 8,
  gA = 0, gB, gC, gD, gE, gF, gG, gH, gI, gJ, gK, gL, gM, gN, gX,
};

constexpr std::int64_t kDist = ax::kDistScale;


SymState ite(const z3::expr& c, const SymState& a, const SymState& b) {
  return {z3::ite(c, a.phase, b.phase),         z3::ite(c, a.mode, b.mode),
          z3::ite(c, a.dir, b.dir),             z3::ite(c, a.jog_dir, b.jog_dir),
          z3::ite(c, a.level, b.level),         z3::ite(c, a.latch_min, b.latch_min),
          z3::ite(c, a.latch_max, b.latch_max), z3::ite(c, a.homed, b.homed),
          z3::ite(c, a.pos, b.pos),             z3::ite(c, a.target, b.target),
          z3::ite(c, a.v, b.v),                 z3::ite(c, a.frac, b.frac)};
}

}  // namespace

Encoder::Encoder(z3::context& ctx, Kernels k, Sem s)
    : c(ctx), kernels(k), sem(s), vstart(s == Sem::Int ? ctx.int_val(0) : ctx.bv_val(0, 32)),
      dd_fun(s == Sem::Int ? ctx.function("DDi", ctx.int_sort(), ctx.int_sort(), ctx.int_sort(), ctx.int_sort())
                           : ctx.function("DD", ctx.bv_sort(32), ctx.bv_sort(32), ctx.bv_sort(32), ctx.bv_sort(64))) {}

z3::expr Encoder::lit(std::int64_t v, unsigned bits) const {
  if (sem == Sem::Int) return c.int_val(v);
  return bits == 64 ? c.bv_val(v, 64) : c.bv_val(static_cast<int>(v), bits);
}
z3::expr Encoder::W(const z3::expr& e) const {
  if (sem == Sem::Int) return e;
  return z3::sext(e, 64 - e.get_sort().bv_size());
}
// static_cast<int32_t>(int64): the low 32 bits (lossless where the no-overflow checks hold, so
// in Int the value itself).
z3::expr Encoder::lo32(const z3::expr& e) const { return sem == Sem::Int ? e : e.extract(31, 0); }
// Unsigned comparisons of uint8 fields (in Int the field's value is already 0..255).
z3::expr Encoder::ule(const z3::expr& a, int b) const { return sem == Sem::Int ? a <= b : z3::ule(a, b); }
z3::expr Encoder::ugt(const z3::expr& a, int b) const { return sem == Sem::Int ? a > b : z3::ugt(a, b); }
z3::expr Encoder::var(const std::string& name, unsigned bits) const {
  return sem == Sem::Int ? c.int_const(name.c_str()) : c.bv_const(name.c_str(), bits);
}
void Encoder::rec(const std::string& name, const z3::expr& guard, const std::function<z3::expr()>& cond) {
  // The side conditions are bit-vector predicates, proved on the Bv encoding
  // (axis.overflow.step); the Int encoding relies on that proof and records none.
  if (sem == Sem::Bv) checks.push_back({name, guard, cond()});
}
Checks* Encoder::arith_checks() { return sem == Sem::Bv ? &checks : nullptr; }

// The C++ type ranges of every field: implicit in the Bv widths, explicit in Int.
namespace {
z3::expr in_type(z3::context& c, const z3::expr& e, std::int64_t lo, std::int64_t hi) {
  return e >= c.int_val(lo) && e <= c.int_val(hi);
}
z3::expr u8(z3::context& c, const z3::expr& e) { return in_type(c, e, 0, 255); }
z3::expr i8(z3::context& c, const z3::expr& e) { return in_type(c, e, -128, 127); }
z3::expr i32(z3::context& c, const z3::expr& e) {
  return in_type(c, e, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max());
}
}  // namespace
z3::expr Encoder::domain(const SymConfig& k) const {
  if (sem == Sem::Bv) return c.bool_val(true);
  return i32(c, k.v_start) && i32(c, k.v_slow) && i32(c, k.v_fast) && i32(c, k.accel) && i32(c, k.soft_min) &&
         i32(c, k.soft_max) && i32(c, k.home_travel) && i32(c, k.home_position);
}
z3::expr Encoder::domain(const SymState& s) const {
  if (sem == Sem::Bv) return c.bool_val(true);
  return u8(c, s.phase) && u8(c, s.mode) && i8(c, s.dir) && i8(c, s.jog_dir) && u8(c, s.level) &&
         u8(c, s.latch_min) && u8(c, s.latch_max) && u8(c, s.homed) && i32(c, s.pos) && i32(c, s.target) &&
         i32(c, s.v) && i32(c, s.frac);
}
z3::expr Encoder::domain(const SymInput& in) const {
  if (sem == Sem::Bv) return c.bool_val(true);
  return u8(c, in.kind) && i8(c, in.cdir) && u8(c, in.clevel) && i32(c, in.value) && u8(c, in.endstop_min) &&
         u8(c, in.endstop_max) && u8(c, in.blocked) && u8(c, in.link_alive);
}

SymConfig Encoder::config(const std::string& x) {
  auto v = [&](const char* n) { return var(std::string(n) + x, 32); };
  return {v("v_start"), v("v_slow"), v("v_fast"), v("accel"), v("soft_min"), v("soft_max"), v("home_travel"),
          v("home_position")};
}
SymState Encoder::state(const std::string& x) {
  auto v8 = [&](const char* n) { return var(std::string(n) + x, 8); };
  auto v32 = [&](const char* n) { return var(std::string(n) + x, 32); };
  return {v8("phase"), v8("mode"), v8("dir"), v8("jog_dir"), v8("level"), v8("latch_min"), v8("latch_max"),
          v8("homed"), v32("pos"), v32("target"), v32("v"), v32("frac")};
}
SymInput Encoder::input(const std::string& x) {
  auto v8 = [&](const char* n) { return var(std::string(n) + x, 8); };
  return {v8("cmd_kind"), v8("cmd_dir"), v8("cmd_level"), var("cmd_value" + x, 32),
          v8("endstop_min"), v8("endstop_max"), v8("blocked"), v8("link_alive")};
}
SymConfig Encoder::config(const ax::Config& v) {
  return {L32(v.v_start),  L32(v.v_slow),   L32(v.v_fast),      L32(v.accel),
          L32(v.soft_min), L32(v.soft_max), L32(v.home_travel), L32(v.home_position)};
}
SymState Encoder::state(const ax::State& v) {
  return {L8(static_cast<int>(v.phase)), L8(static_cast<int>(v.mode)), L8(v.dir), L8(v.jog_dir),
          L8(v.level), L8(v.latch_min), L8(v.latch_max), L8(v.homed),
          L32(v.pos), L32(v.target), L32(v.v), L32(v.frac)};
}
SymInput Encoder::input(const ax::Input& v) {
  return {L8(static_cast<int>(v.cmd.kind)), L8(v.cmd.dir), L8(v.cmd.level), L32(v.cmd.value),
          L8(v.endstop_min), L8(v.endstop_max), L8(v.blocked), L8(v.link_alive)};
}

// config_valid(): int32 comparisons (signed).
z3::expr Encoder::config_valid(const SymConfig& k) {
  const z3::expr pmax = L32(ax::kPosMax);
  return k.v_start >= 1 && k.v_start <= k.v_slow && k.v_slow <= k.v_fast && k.v_fast <= L32(ax::kSpeedMax) &&
         k.accel >= 1 && k.accel <= L32(ax::kAccelMax) && k.soft_min >= -pmax && k.soft_min < k.soft_max &&
         k.soft_max <= pmax && k.home_travel >= 1 && k.home_travel <= pmax && k.home_position >= -pmax &&
         k.home_position <= pmax;
}

// state_valid(): uint8 fields compared unsigned, int8/int32 signed.
z3::expr Encoder::state_valid(const SymState& s) {
  const z3::expr pmax = L32(ax::kPosMax);
  const z3::expr one = L8(1);
  const z3::expr m1 = L8(-1);
  return ule(s.phase, 3) && ule(s.mode, 3) && (s.dir == one || s.dir == m1) &&
         (s.jog_dir == one || s.jog_dir == m1) && ule(s.level, 1) && ule(s.latch_min, 1) &&
         ule(s.latch_max, 1) && ule(s.homed, 1) && s.pos >= -pmax && s.pos <= pmax && s.target >= -pmax &&
         s.target <= pmax && s.v >= 0 && s.v <= L32(ax::kFineSpeedMax) &&
         ((s.v == 0) == (s.phase == L8(kStop))) && s.frac >= 0 && s.frac < L32(kDist);
}

z3::expr Encoder::dd_pre(const z3::expr& v, const z3::expr& s, const z3::expr& a) const {
  // Preconditions of the lemmas (axis.dd.*): what a valid config and state guarantee.
  // s = v_start * 1000 with v_start the config's (kept by step()), 1 <= v_start <= kSpeedMax.
  return v >= L64(0) && v <= L64(ax::kFineSpeedMax) && s == W(vstart * L32(ax::kSpeedScale)) &&
         vstart >= 1 && vstart <= L32(ax::kSpeedMax) && a >= L64(1) && a <= L64(ax::kAccelMax);
}

z3::expr Encoder::dd_contract(const z3::expr& v, const z3::expr& s, const z3::expr& a, const z3::expr& guard) {
  const z3::expr pre = dd_pre(v, s, a) || guard;
  const z3::expr f = dd_fun(lo32(v), lo32(s), lo32(a));
  const z3::expr va = v - a;
  const z3::expr f2 = dd_fun(lo32(va), lo32(s), lo32(a));
  dd_apps.push_back({lo32(v), lo32(s), lo32(a)});
  dd_apps.push_back({lo32(va), lo32(s), lo32(a)});
  return z3::implies(pre, f >= L64(0) && f <= L64(1'000'000'000'000'000'000LL) &&
                              z3::implies(va <= s, f == L64(0)) && z3::implies(va > s, f == va + f2));
}

z3::expr Encoder::dd(const z3::expr& v, const z3::expr& s, const z3::expr& a, const z3::expr& guard) {
  if (kernels == Kernels::Exact) {
    return stop_distance_fine(Arith(c, sem, arith_checks(), guard), v, s, a);
  }
  // The lemmas hold under their preconditions; where step() calls the kernel they must hold
  // (check dd.pre, proved by axis.overflow.step), so there the contract is asserted under the
  // call's path condition, which spares the solver re-deriving the precondition.
  rec("dd.pre", guard, [&] { return dd_pre(v, s, a); });
  contracts.push_back(dd_contract(v, s, a, guard));
  return z3::ite(v <= s || a <= L64(0), L64(0), dd_fun(lo32(v), lo32(s), lo32(a)));
}

// x * static_cast<int64_t>(d) for an int8 d. Exact: the 64-bit product. Contract mode (proofs):
// d in {-1, 0, 1} is recorded as a side condition and the product written as a select, so
// the solver needs no 64x64 multiplier. Sound: the two agree whenever the recorded side
// conditions hold, and axis.overflow.step proves that they do (see docs/proofs.md).
z3::expr Encoder::mul_dir(const Arith& ar, const z3::expr& x, const z3::expr& d8, const std::string& name) {
  if (kernels == Kernels::Exact) return ar.mul(x, W(d8), name);
  rec(name + ".narrow", ar.guard, [&] { return d8 == L8(1) || d8 == L8(-1) || d8 == L8(0); });
  rec(name, ar.guard, [&] { return x != L64(std::numeric_limits<std::int64_t>::min()); });
  return z3::ite(d8 == L8(1), x, z3::ite(d8 == L8(-1), -x, L64(0)));
}

// x / kDist (rem: x % kDist), C++ int64 truncating division. Contract mode: 0 <= x < 2^31 is
// recorded, and quotient and remainder are fresh 32-bit q, r with x = q*kDist + r, r < kDist
// (no divider circuit; shared by the two uses of the same x). axis.narrowing proves that this
// pins q, r to the 32-bit unsigned quotient and remainder, which equal the int64 ones there.
z3::expr Encoder::div_dist(const Arith& ar, const z3::expr& x, bool rem, const std::string& name) {
  if (kernels == Kernels::Exact) {
    if (sem == Sem::Int) return rem ? z3::mod(x, L64(kDist)) : ar.div(x, L64(kDist), name);  // x >= 0 here
    return rem ? z3::srem(x, L64(kDist)) : ar.div(x, L64(kDist), name);
  }
  rec(name + ".narrow", ar.guard, [&] { return x >= L64(0) && x <= L64(std::numeric_limits<std::int32_t>::max()); });
  for (const auto& d : divs) {
    if (z3::eq(d.x, x)) return sem == Sem::Int ? (rem ? d.r : d.q) : zx(rem ? d.r : d.q);
  }
  const std::string id = std::to_string(divs.size());
  if (sem == Sem::Int) {
    // Floor division by a positive constant: x = q*kDist + r, 0 <= r < kDist (x >= 0 on the
    // path, recorded above, so C++ truncation is the same).
    const z3::expr q = c.int_const(("q!" + id).c_str());
    const z3::expr r = c.int_const(("r!" + id).c_str());
    contracts.push_back(x == q * L64(kDist) + r && r >= 0 && r < L64(kDist));
    divs.push_back({x, q, r});
    return rem ? r : q;
  }
  const z3::expr q = c.bv_const(("q!" + id).c_str(), 32);
  const z3::expr r = c.bv_const(("r!" + id).c_str(), 32);
  const z3::expr x32 = lo32(x);
  contracts.push_back(z3::zext(x32, 32) == z3::zext(q, 32) * L64(kDist) + z3::zext(r, 32) && z3::ult(r, L32(kDist)));
  divs.push_back({x, q, r});
  return zx(rem ? r : q);
}

Encoder::Result Encoder::step(const SymState& s0, const SymInput& in, const SymConfig& k) {
  const z3::expr T = c.bool_val(true);
  const z3::expr one8 = L8(1);
  const z3::expr m18 = L8(-1);
  const z3::expr zero8 = L8(0);
  const z3::expr pmax = L32(ax::kPosMax);
  const z3::expr cfg_ok = config_valid(k);
  const z3::expr ok = cfg_ok && state_valid(s0);
  vstart = k.v_start;

  // ---- invalid config or state: forced stop ---------------------------------------------
  SymState fs = s0;
  fs.phase = L8(kStop);
  fs.mode = L8(kIdle);
  fs.v = L32(0);
  fs.frac = L32(0);
  fs.dir = z3::ite(s0.dir < 0, m18, one8);
  SymOutput fo{L32(0), fs.dir, z3::ite(s0.phase != L8(kStop) && ule(s0.phase, 3), L8(gX), L8(gI)),
               L8(cEStop), z3::ite(cfg_ok, L8(eBadState), L8(eBadConfig)), L32(0)};

  // ---- valid path ------------------------------------------------------------------------
  SymState s = s0;
  s.mode = z3::ite(in.blocked != 0, L8(kIdle), s.mode);

  auto endstop_active = [&](const SymState& st, const z3::expr& d) {
    return z3::ite(d > 0, in.endstop_max != 0 || st.latch_max != 0, in.endstop_min != 0 || st.latch_min != 0);
  };
  auto hard_bound = [&](const SymState& st, const z3::expr& d) {
    return z3::ite(d > 0, z3::ite(st.homed != 0, k.soft_max, pmax), z3::ite(st.homed != 0, k.soft_min, -pmax));
  };
  auto motion_allowed = [&](const SymState& st, const z3::expr& d) {
    const z3::expr b = hard_bound(st, d);
    return !endstop_active(st, d) && z3::ite(d > 0, st.pos < b, st.pos > b);
  };

  // apply_command
  z3::expr estop = c.bool_val(false);
  z3::expr err = L8(eNone);
  {
    const z3::expr kind = in.kind;
    const z3::expr moving_cmd = kind == L8(kCmdJog) || kind == L8(kMoveAbs) || kind == L8(kMoveRel) ||
                                kind == L8(kCmdHome);
    const z3::expr bad_level = moving_cmd && ugt(in.clevel, 1);
    const z3::expr blocked = !bad_level && moving_cmd && in.blocked != 0;
    const z3::expr go = !bad_level && !blocked;
    // Jog
    const z3::expr jog_bad_dir = in.cdir != one8 && in.cdir != m18;
    const z3::expr jog_toward = !jog_bad_dir && endstop_active(s, in.cdir);
    SymState sj = s;
    sj.mode = L8(kJog);
    sj.jog_dir = in.cdir;
    sj.level = in.clevel;
    // MoveAbs / MoveRel: |pos| <= 1e9, value int32 -> int64 sum
    const z3::expr is_abs = kind == L8(kMoveAbs);
    const z3::expr is_move = is_abs || kind == L8(kMoveRel);
    const z3::expr t = z3::ite(is_abs, W(in.value), W(s.pos) + W(in.value));
    rec("cmd.pos+value", ok && go && is_move && s.homed != 0 && !is_abs, [&] { return
                      z3::bvadd_no_overflow(W(s.pos), W(in.value), true) && z3::bvadd_no_underflow(W(s.pos), W(in.value)); });
    const z3::expr not_homed = s.homed == 0;
    const z3::expr out_of = !not_homed && (t < W(k.soft_min) || t > W(k.soft_max));
    const z3::expr d = z3::ite(t > W(s.pos), one8, z3::ite(t < W(s.pos), m18, zero8));
    const z3::expr move_toward = !not_homed && !out_of && d != 0 && endstop_active(s, d);
    rec("cmd.target_cast", ok && go && is_move && !not_homed && !out_of && !move_toward, [&] { return
                      t >= L64(std::numeric_limits<std::int32_t>::min()) &&
                          t <= L64(std::numeric_limits<std::int32_t>::max()); });
    SymState sm = s;
    sm.mode = L8(kPosition);
    sm.target = lo32(t);
    sm.level = in.clevel;
    // Home
    const z3::expr on_min = s.phase == L8(kStop) && endstop_active(s, m18);
    SymState sh0 = s;
    sh0.pos = k.home_position;
    sh0.homed = one8;
    sh0.mode = L8(kIdle);
    SymState sh = s;
    sh.mode = L8(kHome);
    sh.homed = zero8;
    sh.level = zero8;
    const z3::expr hb = W(s.pos) - W(k.home_travel);
    rec("cmd.pos-home_travel", ok && go && kind == L8(kCmdHome) && !on_min, [&] { return
                      z3::bvsub_no_overflow(W(s.pos), W(k.home_travel)) &&
                          z3::bvsub_no_underflow(W(s.pos), W(k.home_travel), true); });
    sh.target = z3::ite(hb < L64(-ax::kPosMax), -pmax, lo32(hb));
    SymState si = s;
    si.mode = L8(kIdle);

    const z3::expr known = kind == L8(kNone) || kind == L8(kCmdStop) || kind == L8(kCmdEStop) ||
                           moving_cmd;
    SymState r = s;
    r = ite(go && (kind == L8(kCmdStop) || kind == L8(kCmdEStop)), si, r);
    r = ite(go && kind == L8(kCmdJog) && !jog_bad_dir && !jog_toward, sj, r);
    r = ite(go && is_move && !not_homed && !out_of && !move_toward, sm, r);
    r = ite(go && kind == L8(kCmdHome), ite(on_min, sh0, sh), r);
    estop = go && kind == L8(kCmdEStop);
    err = z3::ite(bad_level, L8(eBadCommand),
          z3::ite(blocked, L8(eBlocked),
          z3::ite(!known, L8(eBadCommand),
          z3::ite(kind == L8(kCmdJog) && jog_bad_dir, L8(eBadCommand),
          z3::ite(kind == L8(kCmdJog) && jog_toward, L8(eTowardEndstop),
          z3::ite(is_move && not_homed, L8(eNotHomed),
          z3::ite(is_move && out_of, L8(eOutOfLimits),
          z3::ite(is_move && move_toward, L8(eTowardEndstop), L8(eNone)))))))));
    s = r;
  }
  s.mode = z3::ite(in.link_alive == 0 && s.mode == L8(kJog), L8(kIdle), s.mode);
  s.latch_min = z3::ite(in.endstop_min != 0, one8, s.latch_min);
  s.latch_max = z3::ite(in.endstop_max != 0, one8, s.latch_max);

  // goal_of
  const z3::expr level_speed = z3::ite(s.level != 0, k.v_fast, k.v_slow);
  const z3::expr kScale = L64(ax::kSpeedScale);
  rec("goal.pr_fine", ok, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(W(level_speed) * kScale); });
  rec("goal.home_pr_fine", ok, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(W(k.v_slow) * kScale); });
  const z3::expr is_jog = s.mode == L8(kJog);
  const z3::expr is_pos = s.mode == L8(kPosition);
  const z3::expr is_home = s.mode == L8(kHome);
  const z3::expr pd = z3::ite(s.target > s.pos, one8, z3::ite(s.target < s.pos, m18, zero8));
  const z3::expr g_dir =
      z3::ite(is_jog, z3::ite(motion_allowed(s, s.jog_dir), s.jog_dir, zero8),
      z3::ite(is_pos, z3::ite(pd != 0 && motion_allowed(s, pd), pd, zero8),
      z3::ite(is_home, z3::ite(s.pos > s.target && motion_allowed(s, m18), m18, zero8), zero8)));
  // level_speed * kSpeedScale written as ite(level, v_fast * 1000, v_slow * 1000) (the same value):
  // the proofs relate the three config products once (axis.config.fine_speeds).
  const z3::expr vs_fine = k.v_slow * L32(ax::kSpeedScale);
  const z3::expr vf_fine = k.v_fast * L32(ax::kSpeedScale);
  const z3::expr g_pr = z3::ite(is_home, vs_fine, z3::ite(s.level != 0, vf_fine, vs_fine));
  const z3::expr g_bound = z3::ite(is_jog, hard_bound(s, s.jog_dir), z3::ite(is_pos || is_home, s.target, L32(0)));
  // Position and Home: the bound may be overrun above the start speed (axis.cpp goal_of, 861dc0a).
  const z3::expr g_pass_ok = is_pos || is_home;

  const z3::expr s_fine = k.v_start * L32(ax::kSpeedScale);
  rec("s_fine", ok, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(W(k.v_start) * kScale); });
  const z3::expr a = k.accel;
  const z3::expr moving = s.phase != L8(kStop);

  // classify
  const z3::expr c_estop = estop;
  const z3::expr c_start = !estop && !moving;
  const z3::expr c_endmin = !estop && moving && s.dir < 0 && endstop_active(s, m18);
  const z3::expr c_endmax = !estop && moving && !c_endmin && s.dir > 0 && endstop_active(s, one8);
  const z3::expr run = ok && !estop && moving && !c_endmin && !c_endmax;
  const z3::expr v = s.v;
  rec("v-a", run, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(W(v) - W(a)); });
  const z3::expr v_brake = z3::ite(v - a > s_fine, v - a, z3::ite(v > s_fine, s_fine, v));
  const z3::expr reverse = g_dir != s.dir;
  const z3::expr rev_halt = reverse && v <= s_fine;
  // same direction: fine_distance(s, bound) = ((bound - pos) * dir) * kDist - frac, int64
  const z3::expr fw = run && !reverse;
  Arith A64(c, sem, arith_checks(), fw);
  const z3::expr d_steps = mul_dir(A64, A64.sub(W(g_bound), W(s.pos), "room.bound-pos"), s.dir, "room.*dir");
  const z3::expr room = A64.sub(A64.mul(d_steps, L64(kDist), "room.*kDist"), W(s.frac), "room.-frac");
  const z3::expr pr = g_pr;
  rec("v+a", fw && v < pr, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(W(v) + W(a)); });
  const z3::expr hi = z3::ite(v < pr, z3::ite(v + a < pr, v + a, pr), z3::ite(v - a > pr, v - a, pr));
  const z3::expr lo = z3::ite(v_brake < hi, v_brake, hi);
  const z3::expr dd_hi = dd(W(hi), W(s_fine), W(a), fw && !(hi <= s_fine));
  rec("can_stop.v+dd", fw && !(hi <= s_fine), [&] { return
                    z3::bvadd_no_overflow(W(hi), dd_hi, true) && z3::bvadd_no_underflow(W(hi), dd_hi); });
  const z3::expr can_hi = hi <= s_fine || W(hi) + dd_hi < room;
  if (kernels == Kernels::Contract) {
    // axis.dd.monotone at (v_brake, hi): v + DD(v) grows with v.
    const z3::expr dd_vb = dd(W(v_brake), W(s_fine), W(a), c.bool_val(false));
    contracts.push_back(z3::implies(fw && v_brake > s_fine && v_brake <= hi, W(v_brake) + dd_vb <= W(hi) + dd_hi));
  }
  z3::expr bf(c);
  if (kernels == Kernels::Exact) {
    bf = lo32(best_fit(Arith(c, sem, arith_checks(), fw && !can_hi), W(lo), W(hi), room, W(s_fine), W(a)));
  } else {
    bf = var("best_fit!" + std::to_string(fresh++), 32);
    // Contract proved as axis.best_fit.contract (preconditions as stated there).
    const z3::expr pre = W(lo) >= L64(1) && lo <= hi && W(hi) <= L64(ax::kFineSpeedMax) &&
                         room >= L64(1) && room <= L64(3'000'000'000'000'000LL) &&
                         W(s_fine) >= L64(1000) && W(s_fine) <= L64(ax::kFineSpeedMax) && a >= 1 &&
                         a <= L32(ax::kAccelMax);
    const z3::expr dd_bf = dd(W(bf), W(s_fine), W(a), c.bool_val(false));
    const z3::expr dd_lo = dd(W(lo), W(s_fine), W(a), c.bool_val(false));
    const z3::expr can_lo = lo <= s_fine || W(lo) + dd_lo < room;
    // ... and when even full braking (lo) cannot stop in time, best_fit brakes fully: bf = lo.
    contracts.push_back(z3::implies(pre || (fw && !can_hi), lo <= bf && bf <= hi &&
                                             z3::implies(can_lo, bf <= s_fine || W(bf) + dd_bf < room) &&
                                             z3::implies(!can_lo, bf == lo)));
    rec("best_fit.pre", fw && !can_hi, [&] { return pre; });
    bf_calls.push_back({bf, W(lo), W(hi), room, W(s_fine), W(a)});
  }
  const z3::expr v_next0 = z3::ite(reverse, z3::ite(rev_halt, L32(0), v_brake), z3::ite(can_hi, hi, bf));
  const z3::expr not_halt = run && !rev_halt;
  Arith A2(c, sem, arith_checks(), not_halt);
  const z3::expr raw = div_dist(A2, A2.add(W(s.frac), W(v_next0), "raw.frac+v"), false, "raw./kDist");
  // d_hard: the hard bound only (the homing bound is a goal bound with pass_ok, not a hard one).
  const z3::expr d_hard = mul_dir(A2, A2.sub(W(hard_bound(s, s.dir)), W(s.pos), "d_hard.-pos"), s.dir, "d_hard.*dir");
  const z3::expr same = g_dir == s.dir;
  Arith A5(c, sem, arith_checks(), not_halt && same);
  const z3::expr d_goal = z3::ite(same, mul_dir(A5, A5.sub(W(g_bound), W(s.pos), "d_goal.-pos"), s.dir, "d_goal.*dir"),
                                  L64(std::numeric_limits<std::int64_t>::max()));
  const z3::expr hit_t = not_halt && same && raw >= d_goal && (v_next0 <= s_fine || !g_pass_ok);
  const z3::expr hit_b = not_halt && !hit_t && raw >= d_hard;
  const z3::expr steps = z3::ite(hit_t, d_goal, z3::ite(hit_b, z3::ite(d_hard > 0, d_hard, L64(0)), z3::ite(not_halt, raw, L64(0))));
  const z3::expr v_next = z3::ite(run, v_next0, L32(0));
  const z3::expr cls =
      z3::ite(c_estop, L8(cEStop),
      z3::ite(c_start, z3::ite(g_dir != 0, L8(cFaster), L8(cHalt)),
      z3::ite(c_endmin, L8(cEndMin),
      z3::ite(c_endmax, L8(cEndMax),
      z3::ite(rev_halt || hit_t || hit_b, L8(cHalt),
      z3::ite(v_next > v, L8(cFaster), z3::ite(v_next == v, L8(cSame), L8(cSlower))))))));

  // transition: kTable (edge_for)
  const z3::expr ph = s.phase;
  auto pick = [&](const std::array<int, 7>& row) {
    z3::expr r = L8(gX);
    for (int i = 6; i >= 0; --i) r = z3::ite(cls == L8(i), L8(row[static_cast<std::size_t>(i)]), r);
    return r;
  };
  (void)pick;
  const z3::expr e = sym_edge_for(c, ph, cls);
  auto is = [&](int x) { return e == L8(x); };

  SymState n = s;
  z3::expr o_err = err;
  z3::expr step_speed = L32(0);
  // A
  n.dir = z3::ite(is(gA), g_dir, n.dir);
  n.v = z3::ite(is(gA), s_fine, n.v);
  n.frac = z3::ite(is(gA), L32(0), n.frac);
  // I
  const z3::expr i_pos = is(gI) && s.mode == L8(kPosition);
  const z3::expr i_home = is(gI) && !i_pos && s.mode == L8(kHome) && !estop;
  // Standing in homing on an active (or latched) min switch is the reference point (axis.cpp
  // edge I, motion.md §6, G19); otherwise the homing failed.
  const z3::expr i_ref = i_home && endstop_active(s, m18);
  n.mode = z3::ite(i_pos || i_home, L8(kIdle), n.mode);
  n.pos = z3::ite(i_ref, k.home_position, n.pos);
  n.homed = z3::ite(i_ref, one8, n.homed);
  o_err = z3::ite(i_home && !i_ref, L8(eHomeFailed), o_err);
  // G, H
  const z3::expr gh = is(gG) || is(gH);
  const z3::expr g_home = is(gG) && s.mode == L8(kHome);
  n.pos = z3::ite(g_home, k.home_position, n.pos);
  n.homed = z3::ite(g_home, one8, n.homed);
  // X
  const z3::expr x = is(gX);
  // E
  const z3::expr ee = is(gE);
  const z3::expr e_done = ee && (hit_t || hit_b);
  const z3::expr e_home = e_done && s.mode == L8(kHome);
  // A Position move ends at its target only; a hard stop at the soft limit keeps it (axis.cpp, edge E).
  n.mode = z3::ite(gh || x || (ee && hit_t && s.mode == L8(kPosition)) || (e_done && s.mode == L8(kHome)), L8(kIdle), n.mode);
  o_err = z3::ite(e_home, L8(eHomeFailed), o_err);
  const z3::expr stopping = gh || x || ee;
  // default (B C D F J K L M N)
  const z3::expr dflt = !(is(gA) || is(gI) || gh || x || ee);
  Arith A3(c, sem, arith_checks(), ok && dflt);
  // v_next == v_next0 on every default edge (they are only reached on the `run` path).
  const z3::expr frac_sum = A3.add(W(s.frac), W(v_next0), "raw.frac+v");
  n.v = z3::ite(stopping, L32(0), z3::ite(dflt, v_next, n.v));
  n.frac = z3::ite(stopping, L32(0), z3::ite(dflt, lo32(div_dist(A3, frac_sum, true, "frac.%kDist")), n.frac));
  step_speed = z3::ite(ee, z3::ite(steps > 0, v_next, L32(0)), z3::ite(dflt, v_next, L32(0)));
  // edge_target
  n.phase = z3::ite(is(gA) || is(gJ) || is(gM) || is(gF), L8(kAccel),
            z3::ite(is(gB) || is(gL) || is(gN), L8(kConst),
            z3::ite(is(gC) || is(gD) || is(gK), L8(kDecel),
            z3::ite(is(gE) || is(gG) || is(gH) || is(gX), L8(kStop), s.phase))));
  // pos += dir * steps, int64
  Arith A4(c, sem, arith_checks(), ok);
  const z3::expr npos = A4.add(W(n.pos), mul_dir(A4, steps, n.dir, "pos.dir*steps"), "pos.+");
  rec("pos.cast", ok, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(npos); });
  rec("steps.cast", ok, [&] { return Arith(c, Sem::Bv, nullptr, T).fits32(steps); });
  n.pos = lo32(npos);
  n.latch_min = z3::ite(steps > 0 && n.dir > 0 && in.endstop_min == 0, zero8, n.latch_min);
  n.latch_max = z3::ite(steps > 0 && n.dir < 0 && in.endstop_max == 0, zero8, n.latch_max);
  SymOutput no{lo32(steps), n.dir, e, cls, o_err, step_speed};

  Result r{ite(ok, n, fs), no};
  r.out = {z3::ite(ok, no.steps, fo.steps),   z3::ite(ok, no.dir, fo.dir),     z3::ite(ok, no.edge, fo.edge),
           z3::ite(ok, no.cls, fo.cls),       z3::ite(ok, no.error, fo.error), z3::ite(ok, no.step_speed, fo.step_speed)};
  return r;
}

z3::expr Encoder::no_overflow() const {
  z3::expr all = c.bool_val(true);
  for (const auto& k : checks) all = all && z3::implies(k.guard, k.cond);
  return all;
}

z3::expr Encoder::all_contracts() const {
  z3::expr all = c.bool_val(true);
  for (const auto& k : contracts) all = all && k;
  return all;
}

namespace {
std::int64_t num(const z3::model& m, const z3::expr& e) {
  const z3::expr v = m.eval(e, true);
  if (v.is_int()) return v.get_numeral_int64();
  const unsigned n = e.get_sort().bv_size();
  std::uint64_t u = v.get_numeral_uint64();
  if (n < 64 && (u >> (n - 1)) != 0) u |= ~((std::uint64_t{1} << n) - 1);  // sign-extend
  return static_cast<std::int64_t>(u);
}
template <class T>
T as(const z3::model& m, const z3::expr& e) {
  return static_cast<T>(num(m, e));
}
}  // namespace

ax::State eval_state(const z3::model& m, const SymState& s) {
  ax::State r;
  r.phase = static_cast<ax::Phase>(as<std::uint8_t>(m, s.phase));
  r.mode = static_cast<ax::Mode>(as<std::uint8_t>(m, s.mode));
  r.dir = as<std::int8_t>(m, s.dir);
  r.jog_dir = as<std::int8_t>(m, s.jog_dir);
  r.level = as<std::uint8_t>(m, s.level);
  r.latch_min = as<std::uint8_t>(m, s.latch_min);
  r.latch_max = as<std::uint8_t>(m, s.latch_max);
  r.homed = as<std::uint8_t>(m, s.homed);
  r.pos = as<std::int32_t>(m, s.pos);
  r.target = as<std::int32_t>(m, s.target);
  r.v = as<std::int32_t>(m, s.v);
  r.frac = as<std::int32_t>(m, s.frac);
  return r;
}
ax::Input eval_input(const z3::model& m, const SymInput& in) {
  ax::Input r;
  r.cmd.kind = static_cast<ax::CmdKind>(as<std::uint8_t>(m, in.kind));
  r.cmd.dir = as<std::int8_t>(m, in.cdir);
  r.cmd.level = as<std::uint8_t>(m, in.clevel);
  r.cmd.value = as<std::int32_t>(m, in.value);
  r.endstop_min = as<std::uint8_t>(m, in.endstop_min);
  r.endstop_max = as<std::uint8_t>(m, in.endstop_max);
  r.blocked = as<std::uint8_t>(m, in.blocked);
  r.link_alive = as<std::uint8_t>(m, in.link_alive);
  return r;
}
ax::Config eval_config(const z3::model& m, const SymConfig& c) {
  ax::Config r;
  r.v_start = as<std::int32_t>(m, c.v_start);
  r.v_slow = as<std::int32_t>(m, c.v_slow);
  r.v_fast = as<std::int32_t>(m, c.v_fast);
  r.accel = as<std::int32_t>(m, c.accel);
  r.soft_min = as<std::int32_t>(m, c.soft_min);
  r.soft_max = as<std::int32_t>(m, c.soft_max);
  r.home_travel = as<std::int32_t>(m, c.home_travel);
  r.home_position = as<std::int32_t>(m, c.home_position);
  return r;
}
ax::Output eval_output(const z3::model& m, const SymOutput& o) {
  ax::Output r;
  r.steps = as<std::int32_t>(m, o.steps);
  r.dir = as<std::int8_t>(m, o.dir);
  r.edge = static_cast<ax::Edge>(as<std::uint8_t>(m, o.edge));
  r.cls = static_cast<ax::Class>(as<std::uint8_t>(m, o.cls));
  r.error = static_cast<ax::Error>(as<std::uint8_t>(m, o.error));
  r.step_speed = as<std::int32_t>(m, o.step_speed);
  return r;
}

ax::StepResult eval_step(z3::context& ctx, const ax::State& s, const ax::Input& in, const ax::Config& c, Sem sem) {
  Encoder enc(ctx, Kernels::Exact, sem);
  const auto r = enc.step(enc.state(s), enc.input(in), enc.config(c));
  // Every term is ground: simplify() folds it to a numeral.
  auto g = [](const z3::expr& e) { return ground_value(e); };
  ax::StepResult out;
  out.state.phase = static_cast<ax::Phase>(static_cast<std::uint8_t>(g(r.state.phase)));
  out.state.mode = static_cast<ax::Mode>(static_cast<std::uint8_t>(g(r.state.mode)));
  out.state.dir = static_cast<std::int8_t>(g(r.state.dir));
  out.state.jog_dir = static_cast<std::int8_t>(g(r.state.jog_dir));
  out.state.level = static_cast<std::uint8_t>(g(r.state.level));
  out.state.latch_min = static_cast<std::uint8_t>(g(r.state.latch_min));
  out.state.latch_max = static_cast<std::uint8_t>(g(r.state.latch_max));
  out.state.homed = static_cast<std::uint8_t>(g(r.state.homed));
  out.state.pos = static_cast<std::int32_t>(g(r.state.pos));
  out.state.target = static_cast<std::int32_t>(g(r.state.target));
  out.state.v = static_cast<std::int32_t>(g(r.state.v));
  out.state.frac = static_cast<std::int32_t>(g(r.state.frac));
  out.out.steps = static_cast<std::int32_t>(g(r.out.steps));
  out.out.dir = static_cast<std::int8_t>(g(r.out.dir));
  out.out.edge = static_cast<ax::Edge>(static_cast<std::uint8_t>(g(r.out.edge)));
  out.out.cls = static_cast<ax::Class>(static_cast<std::uint8_t>(g(r.out.cls)));
  out.out.error = static_cast<ax::Error>(static_cast<std::uint8_t>(g(r.out.error)));
  out.out.step_speed = static_cast<std::int32_t>(g(r.out.step_speed));
  return out;
}

}  // namespace ap::model::smt::xy_axis

namespace ap::model::smt::xy_axis {

z3::expr sym_watchdog_tick(z3::context& c, const z3::expr& silent, const z3::expr& valid) {
  const z3::expr lim = c.bv_val(ax::kLinkTimeoutTicks, 16);
  // silent < kLinkTimeoutTicks ? silent + 1 : kLinkTimeoutTicks (uint16 compare, int add, cast)
  return z3::ite(valid, c.bv_val(0, 16), z3::ite(z3::ult(silent, lim), silent + c.bv_val(1, 16), lim));
}

z3::expr sym_link_alive(z3::context& c, const z3::expr& silent) {
  return z3::ult(silent, c.bv_val(ax::kLinkTimeoutTicks, 16));
}

// An 8-bit enum code, or an integer when the operand is one (Sem::Int encoding).
namespace {
z3::expr code(z3::context& c, const z3::expr& like, int v) { return like.is_int() ? c.int_val(v) : c.bv_val(v, 8); }
}  // namespace

z3::expr sym_edge_guard(z3::context& c, int e, const z3::expr& p, const z3::expr& k) {
  auto P = [&](int x) { return p == code(c, p, x); };
  auto K = [&](int x) { return k == code(c, k, x); };
  const z3::expr stop = P(kStop);
  const z3::expr moving = P(kAccel) || P(kConst) || P(kDecel);
  switch (e) {
    case gA: return stop && K(cFaster);
    case gI: return stop && !K(cFaster);
    case gX: return moving && K(cEStop);
    case gG: return moving && K(cEndMin);
    case gH: return moving && K(cEndMax);
    case gE: return moving && K(cHalt);
    case gJ: return P(kAccel) && K(cFaster);
    case gB: return P(kAccel) && K(cSame);
    case gD: return P(kAccel) && K(cSlower);
    case gM: return P(kConst) && K(cFaster);
    case gL: return P(kConst) && K(cSame);
    case gC: return P(kConst) && K(cSlower);
    case gF: return P(kDecel) && K(cFaster);
    case gN: return P(kDecel) && K(cSame);
    case gK: return P(kDecel) && K(cSlower);
    default: return c.bool_val(false);
  }
}

z3::expr sym_edge_for(z3::context& c, const z3::expr& ph, const z3::expr& cls) {
  auto pick = [&](const std::array<int, 7>& row) {
    z3::expr r = code(c, cls, gX);
    for (int i = 6; i >= 0; --i) r = z3::ite(cls == code(c, cls, i), code(c, cls, row[static_cast<std::size_t>(i)]), r);
    return r;
  };
  return z3::ite(ph == code(c, ph, kStop), pick({gI, gI, gI, gI, gA, gI, gI}),
         z3::ite(ph == code(c, ph, kAccel), pick({gX, gG, gH, gE, gJ, gB, gD}),
         z3::ite(ph == code(c, ph, kConst), pick({gX, gG, gH, gE, gM, gL, gC}),
         z3::ite(ph == code(c, ph, kDecel), pick({gX, gG, gH, gE, gF, gN, gK}), code(c, cls, gX)))));
}

std::int64_t ground_value(const z3::expr& e) {
  const z3::expr v = e.simplify();
  if (v.is_int()) return v.get_numeral_int64();
  const unsigned n = v.get_sort().bv_size();
  std::uint64_t u = v.get_numeral_uint64();
  if (n < 64 && (u >> (n - 1)) != 0) u |= ~((std::uint64_t{1} << n) - 1);
  return static_cast<std::int64_t>(u);
}

}  // namespace ap::model::smt::xy_axis
