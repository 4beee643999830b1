// One stepper axis: a pure, total, deterministic step function over POD structs.
//
// Everything is fixed-width integer arithmetic with straight-line code (no loops), so the
// proofs layer can mirror step() 1:1 as bit-vector terms. docs/motion.md gives the graph
// (Obr. 7-16 reconstructed), every range, and the reasoning behind each decision.
#pragma once

#include <array>
#include <cstdint>

namespace ap::xy_axis {

// ---- Units and ranges ------------------------------------------------------------------
// The control tick is 1 ms: 100x finer than the 100 ms command period, short enough that one
// tick of travel at the top speed (1000 usteps) is a tiny fraction of a stopping distance,
// and long enough that a Cortex-M4 at 80 MHz spends < 1 % of its time in step().
inline constexpr int32_t kTickUs = 1000;
inline constexpr int32_t kTicksPerSecond = 1000;
// Speeds are kept in "fine" units of 1/1000 usteps/s, so that a (usteps/s^2) x 1 ms is exactly
// `a` fine units: the speed law loses nothing to integer division (no remainder needed).
inline constexpr int32_t kSpeedScale = 1000;
// Distance in fine units: 1 ustep = 1e6 fine; one tick at fine speed v travels exactly v.
inline constexpr int32_t kDistScale = kSpeedScale * kTicksPerSecond;
inline constexpr int32_t kPosMax = 1'000'000'000;      // |position| and |target| in usteps
inline constexpr int32_t kSpeedMax = 1'000'000;        // usteps/s
inline constexpr int32_t kAccelMax = 10'000'000;       // usteps/s^2
inline constexpr int32_t kFineSpeedMax = kSpeedMax * kSpeedScale;  // 1e9 < 2^31

enum class Phase : uint8_t { Stop = 0, Accel = 1, Const = 2, Decel = 3 };
inline constexpr int kPhaseCount = 4;

enum class Mode : uint8_t { Idle = 0, Jog = 1, Position = 2, Home = 3 };

// Transition letters of Tab. 7-3 plus the edges the table is missing (docs/motion.md):
// M = CONST->ACCEL (second reading of F, gap G7), N = DECEL->CONST (absent, G7),
// X = emergency stop / invalid config or state from a moving phase.
enum class Edge : uint8_t { A, B, C, D, E, F, G, H, I, J, K, L, M, N, X };
inline constexpr int kEdgeCount = 15;

// The input class of one tick: what the classifier concluded from (state, input, config).
enum class Class : uint8_t {
  EStop = 0,   // emergency stop, or invalid config / state
  EndMin = 1,  // moving toward min and the min endstop is active
  EndMax = 2,  // moving toward max and the max endstop is active
  Halt = 3,    // speed becomes 0 at <= start speed (arrival, stop request, nothing to do)
  Faster = 4,  // the new speed is higher (includes the start jump 0 -> start speed)
  Same = 5,
  Slower = 6,
};
inline constexpr int kClassCount = 7;

enum class CmdKind : uint8_t { None = 0, Jog = 1, Stop = 2, MoveAbs = 3, MoveRel = 4, Home = 5, EStop = 6 };

enum class Error : uint8_t {
  None = 0,
  BadCommand,     // unknown kind, dir not +-1, level not 0/1
  OutOfLimits,    // absolute/relative target outside [soft_min, soft_max]
  Blocked,        // motion command while the board is blocked
  TowardEndstop,  // motion toward an active (or not yet left) endstop
  NotHomed,       // positioning before the position is known
  HomeFailed,     // homing travelled home_travel without seeing the min endstop
  BadConfig,      // config outside its documented ranges: axis forced to Stop
  BadState,       // state outside its invariant ranges: axis forced to Stop
};

struct Command {
  CmdKind kind = CmdKind::None;
  int8_t dir = 0;      // Jog: +1 / -1
  uint8_t level = 0;   // 0 = slow, 1 = fast (Jog, MoveAbs, MoveRel)
  int32_t value = 0;   // MoveAbs: target usteps; MoveRel: increment usteps
};

struct Input {
  Command cmd{};
  uint8_t endstop_min = 0;  // 0/1, sampled at the start of the tick
  uint8_t endstop_max = 0;
  uint8_t blocked = 0;      // board supervisor: USB / charger / low battery
  uint8_t link_alive = 1;   // from LinkWatchdog (watchdog.hpp)
};

// Ranges (checked by config_valid):
//   1 <= v_start <= v_slow <= v_fast <= kSpeedMax            [usteps/s]
//   1 <= accel <= kAccelMax                                  [usteps/s^2]
//   -kPosMax <= soft_min < soft_max <= kPosMax               [usteps]
//   1 <= home_travel <= kPosMax,  -kPosMax <= home_position <= kPosMax
struct Config {
  int32_t v_start = 160;
  int32_t v_slow = 1600;
  int32_t v_fast = 16000;
  int32_t accel = 8000;
  int32_t soft_min = 0;
  int32_t soft_max = 320'000;
  int32_t home_travel = 400'000;
  int32_t home_position = 0;
};

// Invariant ranges (checked by state_valid):
//   phase, mode in their enums; dir, jog_dir in {-1,+1}; level, latch_*, homed in {0,1}
//   |pos| <= kPosMax, |target| <= kPosMax
//   v in [0, kFineSpeedMax], v == 0 iff phase == Stop          [1/1000 usteps/s]
//   frac in [0, kDistScale)                                   [1e-6 usteps travelled since the last step]
struct State {
  Phase phase = Phase::Stop;
  Mode mode = Mode::Idle;
  int8_t dir = 1;          // the DIR pin
  int8_t jog_dir = 1;
  uint8_t level = 0;
  uint8_t latch_min = 0;   // set by the min endstop, cleared after a step away with the input off
  uint8_t latch_max = 0;
  uint8_t homed = 0;       // position known: soft limits enforced, positioning allowed
  int32_t pos = 0;         // the step counter (AP)
  int32_t target = 0;      // PP in Position mode; the homing bound in Home mode
  int32_t v = 0;           // AR in fine units (AR = v / kSpeedScale usteps/s)
  int32_t frac = 0;
};

struct Output {
  int32_t steps = 0;       // steps emitted this tick, 0..1000, all in direction `dir`
  int8_t dir = 1;          // DIR pin during those steps
  Edge edge = Edge::I;
  Class cls = Class::Halt;
  Error error = Error::None;
  int32_t step_speed = 0;  // fine speed the steps of this tick were emitted at
};

struct StepResult {
  State state;
  Output out;
};

[[nodiscard]] bool config_valid(const Config& c);
[[nodiscard]] bool state_valid(const State& s);

// The step function: one control tick. Total: any bit pattern of its arguments gives a
// defined result (bad config or state -> forced Stop with an error).
[[nodiscard]] StepResult step(const State& s, const Input& in, const Config& c);

// Transition table: exactly one edge per (phase, class). edge_guard() states each letter's
// condition separately so a test can check the table is total and deterministic.
[[nodiscard]] Edge edge_for(Phase p, Class c);
[[nodiscard]] bool edge_guard(Edge e, Phase p, Class c);
[[nodiscard]] Phase edge_target(Edge e, Phase from);
[[nodiscard]] char edge_letter(Edge e);
[[nodiscard]] const char* phase_name(Phase p);
[[nodiscard]] const char* mode_name(Mode m);

// Discrete deceleration distance from fine speed v down to the start speed, in fine units
// (1e-6 usteps): the exact sum of the speeds of the ticks still above the start speed when
// braking at `accel` per tick. It never exceeds the continuous DD = (v^2 - s^2) / (2a).
// Ranges: v, v_start_fine <= 1e9, accel >= 1  ->  result <= 5e17 < 2^63.
[[nodiscard]] int64_t stop_distance_fine(int32_t v, int32_t v_start_fine, int32_t accel);

}  // namespace ap::xy_axis
