// The echo reference model (echo_model.hpp) at power-up and at the start of every tick, before
// the tick's frames: the parameter set the boot loads and the sensors it configures last
// (docs/board.md "Step counter and boot"), the block with its battery hysteresis, its entry
// and its exit (docs/board.md "One cycle (tick) in order" step 2; "Decisions on the seed's
// gaps" G16, G23), the BLE session gate (G15) and the button's off request (docs/board.md
// "Button and shutdown"). Its own file because the rest of the model reads the state these set
// up; the rest is split by concern, one file each:
//   dispatch.cpp        a frame event: session, table check, delivery window, the handlers
//   parameters.cpp      the parameter commands and the um <-> ustep conversions
//   path.cpp            the coordinated path: segments queued, stopped, at rest
//   path_verdict.cpp    whether a path frame is refused
//   end_tick.cpp        after the axes stepped: what ended each axis's motion
//   sensors.cpp         the I2C sensors' schedule and error policy
//   echo_content.cpp    the expected echoes, and their comparison with the echoes sent
// Every rule cites the document it comes from; none is taken from core/xy/board
// (docs/echo-model.md).
#include "models/xy/echo/echo_model.hpp"

#include <cstdint>
#include <string>

namespace ap::model::xy_echo {
namespace {

using xy_codec::EchoStatus;

// docs/board.md G23.
constexpr std::int32_t kBatteryHysteresisMv = 100;
constexpr std::int32_t kFaultBadParams = 4000;   // docs/board.md "Power-up": defaults used

}  // namespace

EchoModel::EchoModel(const Boot& boot) {
  for (std::size_t a = 0; a < kAxes; ++a) {
    ax_[a].homed = boot.homed[a];
    ax_[a].last.pos = boot.pos[a];
    ax_[a].latch_min = boot.endstop_min[a];
    ax_[a].latch_max = boot.endstop_max[a];
  }
  if (boot.params) {
    const xy_storage::ParameterSet& f = *boot.params;
    Params n = p_;
    n.accel = static_cast<std::int32_t>(f.max_acceleration_um_s2);
    n.fast = static_cast<std::int32_t>(f.fast_speed_um_s);
    n.slow = static_cast<std::int32_t>(f.slow_speed_um_s);
    n.start = static_cast<std::int32_t>(f.start_speed_um_s);
    n.homing = static_cast<std::int32_t>(f.homing_speed_um_s);
    n.homing_mode = f.homing_mode;
    n.pitch = static_cast<std::int32_t>(f.lead_pitch_um);
    n.steps = f.steps_per_rev;
    n.micro = f.microsteps;
    n.irun = f.run_current_cs;
    n.ihold = f.hold_current_cs;
    n.soft_min = {f.soft_min_x_um, f.soft_min_y_um};
    n.soft_max = {f.soft_max_x_um, f.soft_max_y_um};
    n.home_offset = {f.home_offset_x_um, f.home_offset_y_um};
    n.low_battery = f.low_battery_mv;
    std::string why;
    if (converts(n, why)) {
      p_ = n;
    } else {
      fault_ = kFaultBadParams;
    }
  }
  // docs/board.md "Step counter and boot": the sensors are configured last.
  configure_temperature(boot.sensors);
  configure_gyro(boot.sensors);
}

// ---------------------------------------------------------------- begin of cycle (§7.5.1)
void EchoModel::begin_tick(const Env& env) {
  ++ticks_;
  env_ = env;
  // G23: blocked below the stored threshold, left at threshold + 100 mV.
  if (battery_low_) {
    if (env.battery_mv >= p_.low_battery + kBatteryHysteresisMv) battery_low_ = false;
  } else if (env.battery_mv < p_.low_battery) {
    battery_low_ = true;
  }
  for (auto& x : ax_) {
    x.refused.reset();
    x.started_now = false;
    x.stopped_move_now = false;
  }
  // Priority of causes in the echo: USB > charger > battery (docs/board.md G23).
  const EchoStatus was = block_;
  block_ = env.usb ? EchoStatus::BlockedUsb
           : env.charger ? EchoStatus::BlockedCharger
           : battery_low_ ? EchoStatus::BlockedBattery
                          : EchoStatus::Idle;
  if (was == EchoStatus::Idle && block_ != EchoStatus::Idle) {
    // G16 / motion.md §7: blocking drops every pending move; the axes brake to a stop. What
    // ended a motion before the block (a user stop, the watchdog ending a jog) is the "last
    // event" G16 clears on leaving BLOCKED, also when the axis still brakes then
    // (docs/echo-model.md "Decisions"). It is decided now, not when the braking ends: an
    // answer to a repeat during the block shows it (docs/protocol.md "What a repeat answers").
    for (auto& x : ax_) {
      // A move whose carriage comes to rest on its target in the tick the block starts reached
      // it, as with a stop in the tick of arrival (docs/echo-model.md "Decisions").
      if (x.act == Activity::Position) x.stopped_move_now = true;
      if (x.act != Activity::Idle) x.act = Activity::Braking;
      if (x.stop_requested) x.ended = Ended::Stopped;
      else if (x.link_ended) x.ended = Ended::LinkLost;
      x.stop_requested = false;
      x.link_ended = false;
    }
    // cnc.md "Stops": a block is a controlled stop of the path; like the axes' own motion,
    // what ended it is cleared on leaving BLOCKED (G16).
    if (path_.running) path_.stop = PathStop::Block;
  }
  if (was != EchoStatus::Idle && block_ == EchoStatus::Idle) {
    // G16: back to user control with both axes idle and the last event cleared.
    for (auto& x : ax_) x.ended = Ended::None;
  }
  // Tab. 7-2 / G15: only Data Session open (STATUS1 = 0, STATUS2 = 1) carries commands.
  session_ = !env.ble_status1 && env.ble_status2;
  // docs/board.md "Button and shutdown": the off request is served before the tick's frames.
  if (env.button && !button_was_ && !off_requested_) {
    off_requested_ = true;
    sleep_all();
  }
  button_was_ = env.button;
  at_tick_start_ = ax_;
  path_.added = 0;
  events_.clear();
  out_.clear();
  dispatched_this_tick_ = false;
  taken_this_tick_ = false;
  fate_.reset();
}

// G24: the axes get a ramped stop; motion commands are refused until wake.
void EchoModel::sleep_all() {
  sleeping_ = true;
  path_request_stop(PathStop::User);  // cnc.md "Stops": sleep is a controlled stop
  for (std::size_t b = 0; b < kAxes; ++b) {
    supersede(b);
    Ax& y = ax_[b];
    if (y.act != Activity::Idle) {
      // As for a stop: a move that comes to rest on its target in this tick reached it
      // (docs/echo-model.md "Decisions").
      y.stopped_move_now = y.act == Activity::Position;
      y.act = Activity::Braking;
      y.stop_requested = true;
    }
  }
}

}  // namespace ap::model::xy_echo
