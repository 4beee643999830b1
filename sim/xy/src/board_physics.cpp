// The machine around the simulated board's parts (docs/sim.md "The simulated board"): the
// carriages the STEP edges move through the drivers, the RLS Orbis encoders on the screws
// (eq. 7-2 at boot, the zero a homing programs), the Hall endstops, the input pins the core
// samples (GPIO expander, BLE status, power module), the platform's turn under the gyro
// (docs/sim.md "rotate") and the mechanics model's lost-step risk over every STEP edge.
#include <algorithm>
#include <cmath>

#include "sim/xy/board.hpp"

namespace ap::sim::xy {
namespace {

namespace mech = ap::model::xy_mechanics;

// docs/sim.md "rotate": the platform turns at 90 °/s, code 11790 at ±250 °/s (131 LSB per
// °/s, DS-000169 Table 1): 90 m° per 1 ms tick. Every code sent is a multiple of 131, so each
// tick turns the board's integrated angle by whole m° and the last one lands exactly.
constexpr std::int64_t kTurnMdegPerTick = 90;

// The STEP edges of an axis as full steps (every `per_full` microsteps of net travel): the
// mechanics model fits the low-frequency kinematics, which a 16x thinner sequence keeps, and
// its cost grows with the number of steps inside its fit window.
std::vector<mech::Step> full_steps(const std::vector<std::int64_t>& edges_ns, const std::vector<std::int8_t>& dirs,
                                   std::int32_t per_full) {
  std::vector<mech::Step> out;
  out.reserve(edges_ns.size() / static_cast<std::size_t>(std::max(per_full, 1)) + 1);
  std::int64_t pos = 0;
  for (std::size_t i = 0; i < edges_ns.size(); ++i) {
    pos += dirs[i];
    if (pos % per_full == 0) out.push_back({static_cast<double>(edges_ns[i]) * 1e-9, dirs[i]});
  }
  return out;
}

}  // namespace

std::int32_t SimBoard::usteps_per_rev(std::size_t a) const {
  // The chip's own MRES decides how far a STEP edge turns the motor, not the firmware's
  // parameter: a board whose MRES write never arrived moves 1/256 steps (docs/tmc2130.md
  // "Device model").
  return machine_.full_steps * parts_.tmc[a].microsteps();
}

std::int64_t SimBoard::encoder_raw_counts(std::size_t a) const {
  const double revs = carriage_um_[a] / machine_.lead_um;
  return static_cast<std::int64_t>(std::floor(revs * xy_axis::kEncoderCounts + 1e-9));
}

void SimBoard::zero_encoder(std::size_t a, std::int64_t counts) { encoder_offset_[a] = encoder_raw_counts(a) - counts; }

void SimBoard::fill_inputs(xy_board::Inputs& in) {
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    const double c = carriage_um_[a];
    auto level = [](std::int8_t force, bool physical) -> std::uint8_t {
      if (force > 0) return 1;
      if (force < 0) return 0;
      return physical ? 1 : 0;
    };
    in.endstop_min[a] = level(endstop_force_[a][0], c <= endstop_min_um_[a]);
    in.endstop_max[a] = level(endstop_force_[a][1], c >= endstop_max_um_[a]);
    // RLS Orbis: multi-turn count and a 14-bit angle of the screw (one turn = one lead),
    // measured from its programmed zero.
    const std::int64_t total = encoder_raw_counts(a) - encoder_offset_[a];
    const std::int64_t turns = total >= 0 ? total / xy_axis::kEncoderCounts : -((-total + xy_axis::kEncoderCounts - 1) / xy_axis::kEncoderCounts);
    const std::int64_t counts = total - turns * xy_axis::kEncoderCounts;
    // An encoder taken off the board ("encoder off"): it answers nothing valid.
    in.encoder[a] = xy_axis::EncoderReading{static_cast<std::int32_t>(turns), static_cast<std::uint16_t>(counts),
                                         encoder_fitted_ ? std::uint8_t{1} : std::uint8_t{0}};
  }
  in.usb = usb_;
  in.charger = charger_;
  in.button = button_;
  in.battery_mv = battery_mv_;
  // Power module: charging current positive, discharge negative (more while a motor runs).
  const bool running = out_[0].steps != 0 || out_[1].steps != 0;
  // The board's charger enable (Hardware::charger_enable) gates the charging current.
  in.charge_ma = (charger_ || usb_) && charging_enabled_ ? 500 : (running ? -650 : -120);
  switch (ble_) {   // Tab. 7-2: (STATUS1_IND, STATUS2_IND)
    case Ble::Shutdown: in.ble_status1 = true; in.ble_status2 = true; break;
    case Ble::Standby: in.ble_status1 = true; in.ble_status2 = false; break;
    case Ble::Connected: in.ble_status1 = false; in.ble_status2 = false; break;
    case Ble::Session: in.ble_status1 = false; in.ble_status2 = true; break;
  }
}

std::uint16_t SimBoard::expander_word() const { return board_ ? expander_word(board_->inputs()) : 0; }

std::uint16_t SimBoard::expander_word(const xy_board::Inputs& in) const {
  // GPIO expander inputs: bits 0..3 endstops (x min, x max, y min, y max), 4 button,
  // 5 charger detect, 6 USB flag, 7..8 BLE STATUS1/2.
  std::uint16_t w = 0;
  w = static_cast<std::uint16_t>(w | (in.endstop_min[0] != 0 ? 1U : 0U) | (in.endstop_max[0] != 0 ? 2U : 0U));
  w = static_cast<std::uint16_t>(w | (in.endstop_min[1] != 0 ? 4U : 0U) | (in.endstop_max[1] != 0 ? 8U : 0U));
  w = static_cast<std::uint16_t>(w | (button_ ? 16U : 0U) | (in.charger ? 32U : 0U) | (in.usb ? 64U : 0U));
  w = static_cast<std::uint16_t>(w | (in.ble_status1 ? 128U : 0U) | (in.ble_status2 ? 256U : 0U));
  return w;
}

void SimBoard::motor_effect(std::size_t a, const xy_board::MotorOutput& o) {
  out_[a] = o;
  const std::int64_t t0 = static_cast<std::int64_t>(ticks_) * kNsPerTick;
  xy_axis::Output out;
  out.steps = o.steps;   // the STEP pin toggles whatever the driver does with it
  out.dir = o.dir;
  out.step_speed = static_cast<std::int32_t>(std::min<std::uint64_t>(std::uint64_t{o.step_hz} * xy_axis::kSpeedScale,
                                                                     xy_axis::kFineSpeedMax));
  std::vector<std::int64_t> edges;
  clock_[a].tick(t0, out, edges);
  // The driver decides whether the edges turn the motor and how far (the TMC2130 model, in
  // 1/256 full steps; sim/xy/rig/parts.hpp).
  const std::int64_t turned = parts_.turn(a, o.enable, static_cast<std::int64_t>(edges.size()), o.dir);
  const double um_per_256th = static_cast<double>(machine_.lead_um) / (256.0 * machine_.full_steps);
  carriage_um_[a] += um_per_256th * static_cast<double>(turned);
  AxisRec& r = rec_[a];
  if (turned != 0) {
    for (const std::int64_t e : edges) {
      r.edges_ns.push_back(e);
      r.dirs.push_back(o.dir);
    }
  }
  wave_motor(a, t0, o, edges);
}

void SimBoard::sensors_tick() {
  parts_.tmp117.chip.advance_ms(1);
  const std::int64_t left = turn_to_codes_ - turned_codes_;
  const std::int64_t step = std::clamp(left, -kTurnMdegPerTick * kGyroLsbPerDps, kTurnMdegPerTick * kGyroLsbPerDps);
  // In m°/s: step / 131 m° per 1 ms tick; the model's nearest code is then exactly `step`.
  parts_.gyro.chip.set_rate_mdps(static_cast<std::int32_t>(step / kGyroLsbPerDps * 1000));
  turned_codes_ += step;
}

mech::Result SimBoard::mechanics(std::size_t a) const {
  const AxisRec& r = rec_[a];
  mech::Params p;
  p.axis.lead = machine_.lead_um * 1e-6;
  p.axis.microsteps = 1;   // full steps (full_steps() above)
  const std::int32_t per_full = std::max(1, usteps_per_rev(a) / machine_.full_steps);
  const std::vector<mech::Step> steps = full_steps(r.edges_ns, r.dirs, per_full);
  if (steps.empty()) return {};
  return mech::simulate(mech::Model(p), steps);
}

std::size_t SimBoard::lost_step_risks(std::size_t a) {
  if (!risk_cache_[a] || risk_cache_edges_[a] != rec_[a].edges_ns.size()) {
    risk_cache_[a] = mechanics(a).summary.lost_step_risks;
    risk_cache_edges_[a] = rec_[a].edges_ns.size();
  }
  return *risk_cache_[a];
}

}  // namespace ap::sim::xy
