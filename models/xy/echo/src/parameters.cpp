// The parameter commands and the conversions they govern (docs/board.md "Parameters and
// units"): the storage map's range and rule (docs/storage.md "Factory and user parameters"),
// the cross rule, whether the set converts into valid axis configs (docs/motion.md §2 and
// §10), both axes at rest, and the counters rescaled when the mechanics change. Also the
// um <-> ustep conversions with the mechanics in force that the handlers and the path verdicts
// use (nearest for a target, inward for the soft limits, motion.md §10). An accepted path
// blocks every change but the currents (docs/cnc.md "Refusals"). The set the boot loads is
// echo_model.cpp's; the `param` subscriber's readout is echo_content.cpp's.
#include "models/xy/echo/echo_model.hpp"

#include <cstdint>
#include <string>

#include "rounding.hpp"

namespace ap::model::xy_echo {
namespace {

using xy_codec::CommandId;

// docs/motion.md §2 and §10: core ranges in usteps.
constexpr std::int64_t kSpeedMax = 1'000'000;      // usteps/s
constexpr std::int64_t kAccelMax = 10'000'000;     // usteps/s^2
constexpr std::int64_t kPosMax = 1'000'000'000;    // usteps

bool power_of_two(std::int32_t v) { return v > 0 && (v & (v - 1)) == 0; }

}  // namespace

bool EchoModel::any_moving(bool or_started_now) const {
  // At rest (docs/board.md "Parameters and units"): standing and holding no motion (a jog
  // held at its reversal stop or at a soft limit moves again on the next tick; a move is
  // planned with the speeds it started with), and no motion command accepted earlier in this
  // frame (its distance was converted with the mechanics in force then).
  for (std::size_t a = 0; a < kAxes; ++a) {
    const Ax& x = ax_[a];
    if (x.last.phase != Phase::Stop || at_tick_start_[a].act != Activity::Idle || (or_started_now && x.started_now)) {
      return true;
    }
  }
  return false;
}

std::int64_t EchoModel::to_usteps(std::int64_t um) const {
  return div_round_nearest(um * p_.steps * p_.micro, p_.pitch);
}
std::int32_t EchoModel::limit_min(std::size_t a) const {
  return static_cast<std::int32_t>(div_ceil(static_cast<std::int64_t>(p_.soft_min[a]) * p_.steps * p_.micro, p_.pitch));
}
std::int32_t EchoModel::limit_max(std::size_t a) const {
  return static_cast<std::int32_t>(div_floor(static_cast<std::int64_t>(p_.soft_max[a]) * p_.steps * p_.micro, p_.pitch));
}

bool EchoModel::converts(const Params& p, std::string& why) {
  // docs/board.md "Parameters and units": a set that does not convert into valid axis
  // configs is refused; docs/motion.md §2 and §10 give the ranges and the rounding.
  const std::int64_t num = static_cast<std::int64_t>(p.steps) * p.micro;
  const auto conv = [&](std::int64_t um) { return div_round_nearest(um * num, p.pitch); };
  const std::int64_t v_fast = conv(p.fast), v_slow = conv(p.slow);
  std::int64_t v_start = conv(p.start);
  if (v_start < 1) v_start = 1;  // board.md: a start speed of 0 um/s starts at 1 ustep/s
  const std::int64_t acc = conv(p.accel);
  if (v_fast > kSpeedMax || v_slow > kSpeedMax) return why = "speed above 1e6 usteps/s", false;
  if (!(v_start <= v_slow && v_slow <= v_fast)) {
    return why = "speeds out of order in usteps", false;
  }
  if (acc < 1 || acc > kAccelMax) return why = "acceleration outside [1, 1e7] usteps/s^2", false;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const std::int64_t lo = div_ceil(static_cast<std::int64_t>(p.soft_min[a]) * num, p.pitch);
    const std::int64_t hi = div_floor(static_cast<std::int64_t>(p.soft_max[a]) * num, p.pitch);
    if (lo < -kPosMax || hi > kPosMax || lo >= hi) return why = "travel range empty or outside 1e9 usteps", false;
    if (2 * (hi - lo) > kPosMax) return why = "homing travel above 1e9 usteps", false;
    const std::int64_t home = conv(p.home_offset[a]);
    if (home < -kPosMax || home > kPosMax) return why = "home position outside 1e9 usteps", false;
  }
  return true;
}

bool EchoModel::set_param(CommandId id, std::int32_t d, std::string& why) {
  // docs/board.md "Parameters and units": range and rule (storage map) -> cross rules
  // (start <= slow <= fast) -> conversion -> both axes at rest (every
  // parameter except the two currents) -> save -> apply.
  if (id == CommandId::SetIrun) return p_.irun = d, true;
  if (id == CommandId::SetIhold) return p_.ihold = d, true;
  // docs/cnc.md "Refusals": the path was converted and planned with the parameters in force.
  if (path_.running) return why = "a path is active", false;
  Params n = p_;
  switch (id) {
    case CommandId::SetAccel: n.accel = d; break;
    case CommandId::SetFastSpeed: n.fast = d; break;
    case CommandId::SetSlowSpeed: n.slow = d; break;
    case CommandId::SetStartSpeed: n.start = d; break;
    case CommandId::SetPitch:
      if (d < 100 || d > 100000) return why = "pitch outside the storage range 100..100000", false;
      n.pitch = d;
      break;
    case CommandId::SetSteps:
      if (d > 1000) return why = "steps/rev outside the storage range 1..1000", false;
      n.steps = d;
      break;
    case CommandId::SetMicrosteps:
      if (!power_of_two(d)) return why = "microsteps not a power of two", false;
      n.micro = d;
      break;
    default: return why = "not a parameter", false;
  }
  if (!(n.start <= n.slow && n.slow <= n.fast)) return why = "cross rule", false;
  if (!converts(n, why)) return false;
  const bool mechanics = id == CommandId::SetPitch || id == CommandId::SetSteps || id == CommandId::SetMicrosteps;
  if (any_moving(mechanics)) return why = "an axis moves", false;
  // board.md: pitch, steps/rev and microsteps rescale the step counters so the position in
  // um is kept (the model's copy of the counter follows; the next observation overwrites it).
  const std::int64_t old_num = static_cast<std::int64_t>(p_.steps) * p_.micro * n.pitch;
  const std::int64_t new_num = static_cast<std::int64_t>(n.steps) * n.micro * p_.pitch;
  if (old_num != new_num) {
    for (auto& x : ax_) {
      x.last.pos = static_cast<std::int32_t>(div_round_nearest(static_cast<std::int64_t>(x.last.pos) * new_num, old_num));
    }
  }
  p_ = n;
  return true;
}

}  // namespace ap::model::xy_echo
