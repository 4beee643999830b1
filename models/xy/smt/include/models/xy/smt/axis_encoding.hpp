#pragma once
// Bit-precise Z3 encoding of ap::xy_axis::step() (core/xy/axis/src/axis.cpp).
//
// MIRRORS core/xy/axis/src/axis.cpp (step, apply_command, goal_of, classify, transition, the
// validity checks) and core/xy/axis/src/table.cpp (the A-L(+M,N,X) table) with the same
// widths: every State/Input/Config field is a bit-vector of its C++ width (int8/uint8 -> 8,
// int32 -> 32), every int64 intermediate is computed in 64 bits after explicit sign extension
// exactly where the C++ code promotes, and every add/sub/mul/div records a no-overflow side
// condition (Check). They MUST change together: properties/xy/smt/smt_conformance_test.cpp
// evaluates this encoding on random concrete arguments and compares every output field with
// step().
//
// Kernels (stop_distance_fine, best_fit) come from axis_kernels.hpp. With Kernels::Exact
// they are the bit-precise terms; with Kernels::Contract (used by the step-level proofs)
// their results are abstracted: stop_distance_fine by an uninterpreted function DD(v,s,a)
// (congruent, so equal arguments give equal values) and best_fit by a fresh value, each
// constrained only by the lemmas proved about the exact kernels (axis.dd.*, axis.best_fit.*).
// This is sound: a property proved for every value the contract allows holds for the real one.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <z3++.h>

#include "core/xy/axis/axis.hpp"
#include "models/xy/smt/axis_kernels.hpp"

namespace ap::model::smt::xy_axis {

namespace ax = ap::xy_axis;

struct SymConfig {
  z3::expr v_start, v_slow, v_fast, accel, soft_min, soft_max, home_travel, home_position;  // 32
};
struct SymState {
  z3::expr phase, mode, dir, jog_dir, level, latch_min, latch_max, homed;  // 8
  z3::expr pos, target, v, frac;                                           // 32
};
struct SymInput {
  z3::expr kind, cdir, clevel;  // 8
  z3::expr value;               // 32
  z3::expr endstop_min, endstop_max, blocked, link_alive;  // 8
};
struct SymOutput {
  z3::expr steps;  // 32
  z3::expr dir, edge, cls, error;  // 8
  z3::expr step_speed;  // 32
};

enum class Kernels { Exact, Contract };

// Sem::Bv (default): the bit-precise encoding described above. Sem::Int: the same text over
// mathematical integers (fields range-constrained by domain(), casts and widenings the
// identity, no side conditions recorded). On every path where the Bv encoding's side
// conditions hold -- all of them, for every bit pattern (axis.overflow.step) -- each
// operation's exact result is in its C++ type, so both compute the same values; the Int
// encoding lets linear arithmetic (not bit-blasted 64-bit adders and x1000 multipliers) carry
// the step-level inductive proofs. Conformance compares both with step().
struct Encoder {
  z3::context& c;
  Kernels kernels = Kernels::Exact;
  Sem sem = Sem::Bv;
  Checks checks;                    // no-overflow side conditions of the step encoding
  std::vector<z3::expr> contracts;  // kernel lemmas instantiated at the call sites (Contract)
  int fresh = 0;
  struct Div {
    z3::expr x, q, r;
  };
  std::vector<Div> divs;  // Contract mode: shared quotient/remainder of x / kDist
  // Contract mode: every DD(v, s, a) application and every best_fit value with its arguments,
  // so a counterexample can be refined against the exact kernels (axis_obligations.cpp).
  struct DdApp {
    z3::expr v, s, a;
  };
  struct BestFitCall {
    z3::expr bf, lo, hi, room, s, a;  // lo, hi, s, a widened; room int64
  };
  std::vector<DdApp> dd_apps;
  std::vector<BestFitCall> bf_calls;
  z3::expr vstart;  // the config's v_start of the last step() (kernel preconditions)
  z3::func_decl dd_fun;  // DD(v, s, a): int32 x int32 x int32 -> int64 (Contract mode)

  explicit Encoder(z3::context& ctx, Kernels k = Kernels::Exact, Sem s = Sem::Bv);

  // Literals, widening and casts in the encoder's semantics.
  z3::expr lit(std::int64_t v, unsigned bits) const;
  z3::expr L8(std::int64_t v) const { return lit(v, 8); }
  z3::expr L32(std::int64_t v) const { return lit(v, 32); }
  z3::expr L64(std::int64_t v) const { return lit(v, 64); }
  z3::expr W(const z3::expr& e) const;     // int8/int32 -> int64 (sign extension)
  z3::expr lo32(const z3::expr& e) const;  // static_cast<int32_t>(int64)
  z3::expr ule(const z3::expr& a, int b) const;
  z3::expr ugt(const z3::expr& a, int b) const;
  z3::expr var(const std::string& name, unsigned bits) const;
  // Int: every field within its C++ type (true in Bv, where the width says it).
  z3::expr domain(const SymConfig& k) const;
  z3::expr domain(const SymState& s) const;
  z3::expr domain(const SymInput& in) const;

  SymConfig config(const std::string& suffix);
  SymState state(const std::string& suffix);
  SymInput input(const std::string& suffix);
  SymConfig config(const ax::Config& v);
  SymState state(const ax::State& v);
  SymInput input(const ax::Input& v);

  z3::expr config_valid(const SymConfig& c);
  z3::expr state_valid(const SymState& s);

  struct Result {
    SymState state;
    SymOutput out;
  };
  Result step(const SymState& s0, const SymInput& in, const SymConfig& cfg);

  // stop_distance_fine on widened (64-bit) arguments, exact or contract.
  z3::expr dd(const z3::expr& v64, const z3::expr& s64, const z3::expr& a64, const z3::expr& guard);
  // The DD contract instantiated at (v, s, a): what axis.dd.* prove about the exact kernel.
  z3::expr dd_pre(const z3::expr& v64, const z3::expr& s64, const z3::expr& a64) const;
  z3::expr dd_contract(const z3::expr& v64, const z3::expr& s64, const z3::expr& a64, const z3::expr& guard);

  z3::expr mul_dir(const Arith& ar, const z3::expr& x64, const z3::expr& d8, const std::string& name);
  z3::expr div_dist(const Arith& ar, const z3::expr& x64, bool rem, const std::string& name);

  void rec(const std::string& name, const z3::expr& guard, const std::function<z3::expr()>& cond);
  Checks* arith_checks();

  // All side conditions as one formula (each guard -> cond).
  z3::expr no_overflow() const;
  z3::expr all_contracts() const;
};

// Concrete values back from a model (for counterexample traces and conformance).
ax::State eval_state(const z3::model& m, const SymState& s);
ax::Input eval_input(const z3::model& m, const SymInput& in);
ax::Config eval_config(const z3::model& m, const SymConfig& c);
ax::Output eval_output(const z3::model& m, const SymOutput& o);

// Evaluate the exact encoding (bit-precise, or its Int twin) on concrete arguments (conformance).
ax::StepResult eval_step(z3::context& ctx, const ax::State& s, const ax::Input& in, const ax::Config& c,
                         Sem sem = Sem::Bv);

}  // namespace ap::model::smt::xy_axis

namespace ap::model::smt::xy_axis {

// MIRRORS core/xy/axis/include/core/xy/axis/watchdog.hpp watchdog_tick() and link_alive() (16-bit).
z3::expr sym_watchdog_tick(z3::context& c, const z3::expr& silent16, const z3::expr& valid_command);
z3::expr sym_link_alive(z3::context& c, const z3::expr& silent16);

// MIRRORS edge_guard() and edge_for() of core/xy/axis/src/table.cpp (8-bit enum codes).
z3::expr sym_edge_guard(z3::context& c, int edge, const z3::expr& phase8, const z3::expr& cls8);
z3::expr sym_edge_for(z3::context& c, const z3::expr& phase8, const z3::expr& cls8);

// Evaluate a ground term to an integer (bit-vector: sign-extended from its width).
std::int64_t ground_value(const z3::expr& e);

}  // namespace ap::model::smt::xy_axis
