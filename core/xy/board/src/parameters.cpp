// The parameter set on the board (docs/board.md "Parameters and units"), in one place because
// every change runs the same order: derive() converts a stored set into the axes' configs, and
// a parameter command passes the map's range and rule (docs/storage.md "Factory and user
// parameters"), the cross rules, the conversion, both axes at rest, the FRAM write-verify
// (docs/storage.md "API for the board supervisor"), then the counters are rescaled and the
// drivers' currents and microsteps applied (docs/tmc2130.md). Also `save` (G12: a failed write
// latches its fault).
#include "core/xy/board/board.hpp"
#include "core/xy/board/driver_setup.hpp"

#include <algorithm>
#include <array>

#include "protocol/xy/codec/commands.hpp"
#include "core/xy/tmc2130/fields.hpp"

#include "helpers.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
namespace st = ap::xy_storage;
namespace tmc = ap::xy_tmc2130;
using xy_frame::HandlerStatus;

Derived derive(const st::ParameterSet& p) {
  Derived d;
  if (!st::validate(p).ok()) return d;
  d.mech = xy_axis::Mechanics{static_cast<std::int32_t>(p.lead_pitch_um), p.steps_per_rev, p.microsteps};
  if (!xy_axis::mechanics_valid(d.mech)) return d;
  const auto start = xy_axis::speed_to_usteps(static_cast<std::int32_t>(p.start_speed_um_s), d.mech);
  const auto slow = xy_axis::speed_to_usteps(static_cast<std::int32_t>(p.slow_speed_um_s), d.mech);
  const auto fast = xy_axis::speed_to_usteps(static_cast<std::int32_t>(p.fast_speed_um_s), d.mech);
  const auto accel = xy_axis::accel_to_usteps(static_cast<std::int32_t>(p.max_acceleration_um_s2), d.mech);
  if (start.error != xy_axis::Error::None || slow.error != xy_axis::Error::None || fast.error != xy_axis::Error::None ||
      accel.error != xy_axis::Error::None) {
    return d;
  }
  const std::array<std::array<std::int32_t, 3>, kAxes> per_axis{{
      {p.soft_min_x_um, p.soft_max_x_um, p.home_offset_x_um},
      {p.soft_min_y_um, p.soft_max_y_um, p.home_offset_y_um},
  }};
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto lim = xy_axis::limits_to_usteps(per_axis[i][0], per_axis[i][1], d.mech);
    const auto home = xy_axis::um_to_usteps(per_axis[i][2], d.mech, xy_axis::Round::Nearest);
    if (lim.error != xy_axis::Error::None || home.error != xy_axis::Error::None) return d;
    xy_axis::Config& cfg = d.cfg[i];
    // A start speed of 0 µm/s (allowed by the map) or one that rounds to 0 means "start at
    // the lowest speed the step function knows", 1 ustep/s.
    cfg.v_start = std::max<std::int32_t>(start.value, 1);
    cfg.v_slow = slow.value;
    cfg.v_fast = fast.value;
    cfg.accel = accel.value;
    cfg.soft_min = lim.min;
    cfg.soft_max = lim.max;
    // Homing gives up after twice the travel range: from anywhere inside it the min endstop
    // must have been seen by then. span <= 2e9 so the product fits int64.
    const std::int64_t span = static_cast<std::int64_t>(lim.max) - lim.min;
    cfg.home_travel = static_cast<std::int32_t>(std::clamp<std::int64_t>(2 * span, 1, xy_axis::kPosMax));
    cfg.home_position = home.value;
    if (!xy_axis::config_valid(cfg)) return d;
  }
  d.ok = true;
  return d;
}

HandlerStatus Board::on_param(void* ctx, Axis a, std::int32_t value, c::CommandId id) {
  auto* b = static_cast<Board*>(ctx);
  st::ParamId pid = st::ParamId::MaxAcceleration;
  switch (id) {
    case c::CommandId::SetFastSpeed: pid = st::ParamId::FastSpeed; break;
    case c::CommandId::SetSlowSpeed: pid = st::ParamId::SlowSpeed; break;
    case c::CommandId::SetAccel: pid = st::ParamId::MaxAcceleration; break;
    case c::CommandId::SetStartSpeed: pid = st::ParamId::StartSpeed; break;
    case c::CommandId::SetPitch: pid = st::ParamId::LeadPitch; break;
    case c::CommandId::SetSteps: pid = st::ParamId::StepsPerRev; break;
    case c::CommandId::SetMicrosteps: pid = st::ParamId::Microsteps; break;
    case c::CommandId::SetIrun: pid = st::ParamId::RunCurrent; break;
    case c::CommandId::SetIhold: pid = st::ParamId::HoldCurrent; break;
    default: return b->refuse(a, id);
  }
  return b->set_parameter(a, id, pid, value);
}

HandlerStatus Board::set_parameter(Axis a, c::CommandId id, st::ParamId pid, std::int32_t value) {
  param_cycle_ = true;
  const bool current = pid == st::ParamId::RunCurrent || pid == st::ParamId::HoldCurrent;
  // A queued path was converted and planned with the parameters in force (docs/cnc.md).
  if (path_.active() && !current) return refuse(a, id);
  st::ParameterSet next = store_.current();
  if (!st::set_field(next, pid, value) || !st::validate(next).ok()) return refuse(a, id);
  const Derived d = derive(next);
  if (!d.ok) return refuse(a, id);
  const bool mechanics = pid == st::ParamId::LeadPitch || pid == st::ParamId::StepsPerRev || pid == st::ParamId::Microsteps;
  const bool currents = pid == st::ParamId::RunCurrent || pid == st::ParamId::HoldCurrent;
  // Only the currents may change under a moving carriage. A move is planned with the speeds
  // and acceleration it started with: a lower deceleration mid-move would carry the axis
  // past a target it could reach before (found by fuzz/xy/board), and changed mechanics would
  // make the step counter and the target meaningless.
  // At rest also means no motion command earlier in this frame: its distance was converted
  // with the mechanics in force when its handler ran, and a pitch or microstep change would
  // rescale the counter under it (a -60 mm move became -3.75 mm; docs/echo-model.md).
  // At rest also means holding no motion: a jog held at its reversal stop or at a soft limit
  // steps again on the next tick, and the mechanics change below would drop its mode without
  // an event (docs/echo-model.md).
  // A move standing on its target holds nothing (holds_motion).
  if (!currents && (holds_motion(axes_[0]) || holds_motion(axes_[1]) ||
                    (mechanics && (pending_motion(0) == Pending::Accepted || pending_motion(1) == Pending::Accepted)))) {
    return refuse(a, id);
  }
  // A pending motion command the axis core will refuse keeps its refusal now: a change of
  // the mechanics below would rescale the counter under its converted distance.
  for (std::size_t k = 0; k < kAxes; ++k) {
    if (mechanics && pending_motion(k) == Pending::Refused) {
      refused_[k] = static_cast<std::uint8_t>(pending_id_[k]);
      pending_[k] = {};
    }
  }
  const st::SaveResult r = store_.save(next);
  if (!r.ok()) {
    // The store keeps using the previous verified set; so does the board.
    fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
    return HandlerStatus::Done;
  }
  if (mechanics) {
    for (std::size_t i = 0; i < kAxes; ++i) {
      const std::int64_t um = xy_axis::usteps_to_um(axes_[i].pos, derived_.mech);
      const xy_axis::Converted p = xy_axis::um_to_usteps(clamp32(um), d.mech, xy_axis::Round::Nearest);
      if (p.error == xy_axis::Error::None) {
        axes_[i].pos = p.value;
      } else {
        axes_[i].homed = 0;  // not representable any more: the axis must home again
      }
      axes_[i].target = axes_[i].pos;
      axes_[i].mode = xy_axis::Mode::Idle;
      axes_[i].frac = 0;
    }
  }
  derived_ = d;
  if (pid == st::ParamId::RunCurrent || pid == st::ParamId::HoldCurrent) (void)apply_currents();
  if (pid == st::ParamId::Microsteps) (void)apply_microsteps();
  return HandlerStatus::Done;
}

bool Board::apply_currents() {
  const st::ParameterSet& p = store_.current();
  bool ok = true;
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto r = drivers_[i].update(tmc::Reg::IHOLD_IRUN, {{tmc::Field::IHOLD_IRUN_IHOLD, p.hold_current_cs},
                                                             {tmc::Field::IHOLD_IRUN_IRUN, p.run_current_cs}});
    if (!r) {
      driver_fault(i, r.error());
      ok = false;
    }
  }
  return ok;
}

bool Board::apply_microsteps() {
  const std::int64_t mres = mres_of(store_.current().microsteps);
  bool ok = true;
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto r = drivers_[i].set(tmc::Field::CHOPCONF_MRES, mres);
    if (!r) {
      driver_fault(i, r.error());
      ok = false;
    }
  }
  return ok;
}

HandlerStatus Board::on_save(void* ctx, Axis, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  b->param_cycle_ = true;
  const st::SaveResult r = b->store_.save(b->store_.current());
  if (!r.ok()) b->fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
  return HandlerStatus::Done;
}

}  // namespace ap::xy_board
