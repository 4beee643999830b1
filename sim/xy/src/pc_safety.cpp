// The axis safety properties on the telemetry (pc_safety.hpp, docs/sim.md "Safety properties on
// the telemetry"): the PC side's own view of them, beside the board's per-tick monitor.
#include "pc_safety.hpp"

#include <algorithm>
#include <string>

#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/frames.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/text.hpp"
#include "pc_board.hpp"

namespace ap::sim::xy {

void SafetyCheck::left(std::int64_t t, std::span<const std::uint8_t> bytes, std::span<const FrameTag> /*tags*/) {
  if (bytes.empty()) return;
  bool ok_frame = session_;
  for (std::size_t k = 0; ok_frame && k + xy_codec::kCommandLength <= bytes.size(); k += xy_codec::kCommandLength) {
    xy_frame::CommandFrame cf;
    ok_frame = xy_frame::parse_command(bytes.subspan(k, xy_codec::kCommandLength), cf).ok();
  }
  if (ok_frame) last_delivered_us_ = t;
}

void SafetyCheck::sampled(const dds::Telemetry* before, const dds::Telemetry& now) {
  if (before == nullptr || now != *before) {
    for (std::size_t i = 0; i < 2; ++i) {
      prev_[i] = before != nullptr ? before->axis[i] : now.axis[i];
      have_prev_[i] = before != nullptr;
    }
  }
  session_ = now.ble_status == 2;
}

void SafetyCheck::check(PcContext& pc, const BoardPc& b, std::int64_t t) const {
  const PcMech& mech = pc.mech;
  const double dt = static_cast<double>(pc.opt.step_us) / 1e6;
  for (std::size_t i = 0; i < 2; ++i) {
    const dds::AxisTelemetry& n = b.tel.axis[i];
    const char an = i == 0 ? 'x' : 'y';
    auto bad = [&](const std::string& what) {
      pc.fail("safety: board " + std::to_string(b.id) + " axis " + an + " at " + tstr(t) + ": " + what);
    };
    const double v = n.speed * mech.um_per_ustep;
    if (v > mech.max_speed_um_s * 1.01 + 2 * mech.um_per_ustep) {
      bad("speed " + fmt(v) + " um/s above every speed limit the PC set (" + fmt(mech.max_speed_um_s) + " um/s)");
    }
    if (!have_prev_[i]) continue;
    const dds::AxisTelemetry& p = prev_[i];
    if (p.endstop_max && n.endstop_max && n.pos > p.pos) bad("moved toward the active max endstop");
    if (p.endstop_min && n.endstop_min && n.pos < p.pos) bad("moved toward the active min endstop");
    if (p.blocked && n.blocked && n.speed > p.speed) bad("speed increased while the board is blocked");
    if (n.dir != p.dir) {
      const double vp = p.speed * mech.um_per_ustep;
      const double bound = mech.start_um_s + 2.0 * mech.accel_um_s2 * dt + 2 * mech.um_per_ustep;
      if (vp > bound) bad("DIR reversed while moving at " + fmt(vp) + " um/s (start speed " + fmt(mech.start_um_s) + ")");
    }
    // The link watchdog: 3 command periods without a frame reaching the board, then a ramped
    // stop from at most the highest speed at the lowest acceleration ever set.
    const double stop_s = mech.max_speed_um_s / std::max(1.0, mech.min_accel_um_s2);
    const auto bound_us = static_cast<std::int64_t>(3 * pc.s.period_us + static_cast<std::int64_t>(stop_s * 1e6) + 2 * pc.opt.step_us);
    if (b.keys[i].jogging && t - last_delivered_us_ > bound_us && n.speed != 0) {
      bad("still jogging " + tstr(t - last_delivered_us_) + " after the last frame reached the board");
    }
  }
}

}  // namespace ap::sim::xy
