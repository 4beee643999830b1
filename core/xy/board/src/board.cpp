// The supervisor's cycle (docs/board.md "One cycle (tick) in order", "Main states"): the order
// of one tick, power-up (docs/board.md "Step counter and boot"), the button's off request and
// the shutdown it ends with (docs/board.md "Button and shutdown"), the periodic driver check
// (step 6) and the driver fault codes. This file holds the order the steps run in, so the
// cycle reads top to bottom here; what each step does is its concern's file:
//   dispatch.cpp        the constructor's callback table, the receive ring, one frame (step 3)
//   tick_rules.cpp      the block causes, the link watchdog, both axes and their events (2, 4, 5)
//   sensors.cpp         the I2C sensors and the charger enable (step 7)
//   echo.cpp            the echoes and their subscribers (step 8)
//   commands.cpp        the motion, sleep, wake and clear_fault handlers
//   parameters.cpp      the parameter set: derive(), the parameter and save handlers
//   path_commands.cpp   the coordinated path (docs/cnc.md "On the board")
#include "core/xy/board/board.hpp"
#include "core/xy/board/driver_setup.hpp"

#include "helpers.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
namespace st = ap::xy_storage;
namespace tmc = ap::xy_tmc2130;

BootResult Board::boot() {
  BootResult r{};
  r.store = store_.boot();
  derived_ = derive(store_.current());
  if (!derived_.ok) {
    // A set that passed its CRC and range checks but does not convert (e.g. a speed above
    // the step generator's range for this pitch) is not used; the defaults always convert.
    derived_ = derive(st::defaults());
    fault_ = kFaultBadParams;
  }
  r.drivers_ok = true;
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto init = drivers_[i].init();
    if (!init) {
      driver_fault(i, init.error());
      r.drivers_ok = false;
    }
  }
  // Both drivers are configured even if one fails, so a single bad chip does not leave the
  // other at its reset value (TOFF = 0: power stage off; docs/tmc2130.md "Boot configuration").
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto setup = configure_driver(drivers_[i], store_.current());
    if (!setup) {
      driver_fault(i, setup.error());
      r.drivers_ok = false;
    }
  }

  if (hw_.sample != nullptr) hw_.sample(hw_.ctx, in_);
  const st::ParameterSet& p = store_.current();
  const std::array<std::int32_t, kAxes> saved{p.step_count_x, p.step_count_y};
  const auto rev = static_cast<std::int32_t>(xy_axis::usteps_per_rev(derived_.mech));
  for (std::size_t i = 0; i < kAxes; ++i) {
    r.start[i] = xy_axis::start_position(&in_.encoder[i], {saved[i], p.step_counts_valid ? std::uint8_t{1} : std::uint8_t{0}},
                                      rev);
    axes_[i] = xy_axis::initial_state(r.start[i]);
    // An endstop active at power-up may be the switch the carriage rests on: it is latched
    // like one seen while moving, so a bouncing Hall switch cannot let the first move run
    // into it before the carriage has stepped away (docs/motion.md §4, G8).
    axes_[i].latch_min = in_.endstop_min[i] != 0 ? 1 : 0;
    axes_[i].latch_max = in_.endstop_max[i] != 0 ? 1 : 0;
  }
  // Last, so a sensor that fails its configure() shows its fault rather than being hidden
  // behind a storage or driver fault of the same boot.
  configure_temperature();
  configure_gyro();
  return r;
}

void Board::tick() {
  if (powered_off_) return;  // the KillSwitch is pulled; only a power cycle brings the core back
  ++ticks_;
  param_cycle_ = false;
  frame_this_cycle_ = false;
  taken_this_cycle_ = false;
  echo_count_ = 0;
  pending_.fill(xy_axis::Command{});
  pending_id_.fill(c::CommandId::Nop);
  refused_.fill(kNoRefusal);
  path_error_ = xy_path::Error::None;
  begin_of_cycle();
  if (in_.button && !button_was_ && !off_requested_) request_off();
  button_was_ = in_.button;
  receive();
  step_axes();
  check_drivers();
  read_sensors();
  main_state_ = block_ != Block::None ? MainState::Blocked : (param_cycle_ ? MainState::ParamSet : MainState::UserControl);
  // The refusals are final once the axes have stepped (the axis core refuses too).
  if (taken_this_cycle_) last_outcome_ = Outcome{block_, refused_};
  send_echoes();
  if (hw_.led != nullptr) {
    const Led l = led();
    hw_.led(hw_.ctx, led_lit(l, ticks_) ? l.colour : LedColour::Off);
  }
  if (off_requested_ && !moving(axes_[0]) && !moving(axes_[1]) && !path_.active()) finish_shutdown();
}

// Thesis §7.9.5: an off request from the button's controller lets the firmware run a shutdown
// sequence that may save data to FRAM, then the MCU switches itself off through the KillSwitch.
// The axes get the ramped stop `sleep` gives (so the counter saved is where the carriage
// stands), motion is refused from then on, and the sequence ends at the first tick both axes
// stand (docs/board.md "Button and shutdown").
void Board::request_off() {
  off_requested_ = true;
  (void)on_periph_off(this, Axis::X, 0);
}

void Board::finish_shutdown() {
  // The step counters go to FRAM with their validity flag (§7.7.2 "FRAM alternative"): the
  // next boot starts from them when no encoder answers. A failed save latches its fault and
  // the unit still switches off: the user asked for it, and the next boot then starts
  // unhomed (the flag was not written) rather than from a wrong counter.
  (void)shutdown();
  powered_off_ = true;
  if (hw_.power_off != nullptr) hw_.power_off(hw_.ctx);
}

ShutdownResult Board::shutdown() {
  if (moving(axes_[0]) || moving(axes_[1]) || path_.active()) return ShutdownResult::Moving;
  const st::SaveResult r = store_.record_shutdown(axes_[0].pos, axes_[1].pos);
  if (!r.ok()) {
    fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
    return ShutdownResult::StorageFault;
  }
  return ShutdownResult::Ok;
}

void Board::check_drivers() {
  // One GSTAT read per driver every 100 ms, staggered, restores the registers after a chip
  // reset (motor supply dip) without loading the SPI bus every tick.
  const std::uint32_t phase = ticks_ % kDriverCheckPeriod;
  for (std::size_t i = 0; i < kAxes; ++i) {
    if (phase != i * (kDriverCheckPeriod / kAxes)) continue;
    const auto r = drivers_[i].check_reset();
    if (!r) driver_fault(i, r.error());
  }
}

void Board::driver_fault(std::size_t i, tmc::Error e) {
  fault_ = (i == 0 ? kFaultDriverX : kFaultDriverY) + static_cast<std::int32_t>(e);
}

BoardCounters Board::counters() const {
  BoardCounters k = counters_;
  k.framer = framer_.counters();
  return k;
}

}  // namespace ap::xy_board
