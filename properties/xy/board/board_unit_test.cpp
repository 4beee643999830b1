// The board core (core/xy/board) wired to the device models: blocking (G16, G23), BLE session
// gating (G15), the link watchdog, malformed frames, parameter save/reboot/reload, driver
// currents, endstops, the echo at the end of the cycle, the step-counter validity flag.
#include <gtest/gtest.h>

#include "sim/xy/rig/board_rig.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "core/xy/tmc2130/fields.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
using C = xy_codec::CommandId;
using S = xy_codec::EchoStatus;
namespace tmc = ap::xy_tmc2130;

namespace {

xy_frame::SubscriberSlots subs_of(xy_codec::SubscriberId id, std::uint8_t arg = 0) {
  xy_frame::SubscriberSlots s{};
  s[0] = {id, arg};
  return s;
}

// Keeps a jog alive the way the PC does: one frame every 100 ms.
void jog_for(Rig& r, Axis a, std::int32_t level, int ticks) {
  for (int t = 0; t < ticks; ++t) {
    if (t % 100 == 0) {
      if (a == Axis::X) {
        r.send(C::Jog, level);
      } else {
        r.send(C::Nop, 0, C::Jog, level);
      }
    }
    r.tick();
  }
}

}  // namespace

TEST(BoardBoot, BlankFramGivesDefaultsAndDriversGetStoredCurrents) {
  Rig r;
  const BootResult b = r.boot();
  EXPECT_TRUE(b.store.defaults_used());
  EXPECT_TRUE(b.drivers_ok);
  const auto d = xy_storage::defaults();
  for (auto& chip : r.tmc) {
    const std::uint32_t w = chip.chip_register(tmc::Reg::IHOLD_IRUN);
    EXPECT_EQ(tmc::field_get(w, tmc::Field::IHOLD_IRUN_IRUN), d.run_current_cs);
    EXPECT_EQ(tmc::field_get(w, tmc::Field::IHOLD_IRUN_IHOLD), d.hold_current_cs);
    EXPECT_EQ(tmc::field_get(chip.chip_register(tmc::Reg::CHOPCONF), tmc::Field::CHOPCONF_MRES), 4);  // 16 usteps
  }
  EXPECT_EQ(r.board->main_state(), MainState::UserControl);
  EXPECT_EQ(r.ax(Axis::X).homed, 0);  // no encoder, no valid counter
}

// docs/tmc2130.md "Boot configuration": the register words every driver holds after boot,
// written out from that table (defaults: 16 microsteps, run 16, hold 8, SGT 0).
TEST(BoardBoot, EveryDriverIsConfiguredAndSwitchedOn) {
  Rig r;
  ASSERT_TRUE(r.boot().drivers_ok);
  for (auto& chip : r.tmc) {
    // TOFF 3, HSTRT 4 (bits 6..4), HEND 1 (bits 10..7), TBL 2 (bits 16..15), chm 0, vsense 0,
    // MRES 4 (bits 27..24), intpol 1 (bit 28).
    EXPECT_EQ(chip.chip_register(tmc::Reg::CHOPCONF), 0x3u | (4u << 4) | (1u << 7) | (2u << 15) | (4u << 24) | (1u << 28));
    // diag0_error (5), diag0_otpw (6), diag1_stall (8); en_pwm_mode (2) off: SpreadCycle.
    EXPECT_EQ(chip.chip_register(tmc::Reg::GCONF), (1u << 5) | (1u << 6) | (1u << 8));
    EXPECT_EQ(chip.chip_register(tmc::Reg::IHOLD_IRUN), (6u << 16) | (16u << 8) | 8u);
    EXPECT_EQ(chip.chip_register(tmc::Reg::TPOWERDOWN), 10u);
    EXPECT_EQ(chip.chip_register(tmc::Reg::TCOOLTHRS), 0xFFFFFu);
    EXPECT_EQ(chip.chip_register(tmc::Reg::COOLCONF), 0u);  // SGT 0, CoolStep off (semin 0)
    EXPECT_TRUE(chip.power_stage_on());
  }
}

// The motor turns as far as the axis asked: 10 mm at a 2 mm lead is 5 turns, 1000 full steps
// of a 200-step motor, in the chip's 1/256 steps (the TMC2130 model moves nothing while its
// power stage is off, so a board that never switched its drivers on fails here).
TEST(BoardBoot, AGotoTurnsTheMotorThroughTheDriver) {
  Rig r;
  r.in.encoder[0] = {0, 0, 1};  // absolute position 0 at power-up: the axis is referenced
  r.boot();
  r.send(C::Goto, 10000);
  for (int t = 0; t < 4000 && r.rotor_256[0] != 1000 * 256; ++t) {
    if (t % 100 == 99) r.send(C::Nop, 0);
    r.tick();
  }
  EXPECT_EQ(r.rotor_256[0], 1000 * 256);
  EXPECT_EQ(r.steps_total[0], 16000);
}

// Thesis §7.9.5 and §7.7.2 "FRAM alternative": the button's off request runs the shutdown
// sequence (the carriage brakes, the step counters go to FRAM with their validity flag), then
// the KillSwitch; a board without an encoder starts from the saved counter at the next
// power-up (docs/board.md "Button and shutdown").
TEST(BoardShutdown, TheButtonSavesTheCounterAndPullsTheKillSwitch) {
  Rig r;
  r.in.endstop_min[0] = 1;  // no encoder; the carriage rests on its min switch: homing completes at once
  r.boot();
  r.send(C::Home, 0);
  r.tick();
  ASSERT_EQ(r.ax(Axis::X).homed, 1);
  r.in.endstop_min[0] = 0;
  r.send(C::Goto, 10000);  // 10 mm = 5 turns of a 2 mm screw = 16000 usteps at 16 x 200
  for (int t = 0; t < 1500; ++t) {
    if (t % 100 == 99) r.send(C::Nop, 0);
    r.tick();
  }
  r.send(C::Jog, 2);  // moving when the button is pressed
  r.tick(50);
  ASSERT_NE(r.ax(Axis::X).phase, xy_axis::Phase::Stop);
  r.in.button = true;  // the controller's off request (released since power-up)
  int t = 0;
  for (; t < 3000 && r.kill_switch_pulls == 0; ++t) r.tick();
  EXPECT_EQ(r.kill_switch_pulls, 1);
  EXPECT_TRUE(r.board->powered_off());
  EXPECT_EQ(r.ax(Axis::X).phase, xy_axis::Phase::Stop);
  const std::int32_t stood = r.ax(Axis::X).pos;
  EXPECT_GT(stood, 16000);  // it braked from the jog, forward
  const auto ticks = r.board->ticks();
  r.tick(10);
  EXPECT_EQ(r.board->ticks(), ticks) << "a switched-off core runs no more ticks";
  EXPECT_EQ(r.kill_switch_pulls, 1);
  // Power-up with no encoder: the saved counter, homed.
  r.in.button = false;
  r.boot();
  EXPECT_EQ(r.ax(Axis::X).pos, stood);
  EXPECT_EQ(r.ax(Axis::X).homed, 1);
}

// The press that switched the unit on is not an off request: the line must be released first.
TEST(BoardShutdown, APressHeldThroughPowerUpIsNotAnOffRequest) {
  Rig r;
  r.in.button = true;
  r.boot();
  r.tick(100);
  EXPECT_FALSE(r.board->off_requested());
  r.in.button = false;
  r.tick();
  r.in.button = true;
  r.tick();
  EXPECT_TRUE(r.board->off_requested());
}

// docs/board.md "Charger disconnect": the charging circuit is disconnected while the board's
// TMP117 reads outside 0..45 °C and reconnected 2 °C inside that window.
TEST(BoardCharger, DisconnectedOutsideTheChargeTemperatureWindow) {
  Rig r;
  r.tmp117.chip.set_temperature_mc(25'000);
  r.boot();
  r.tick(600);
  ASSERT_EQ(r.charger_enables, std::vector<bool>{true});
  const auto settle = [&](std::int32_t mc) {
    r.tmp117.chip.set_temperature_mc(mc);
    r.tick(600);  // two conversions and a read
    return r.board->charging_allowed();
  };
  EXPECT_TRUE(settle(45'000));
  EXPECT_FALSE(settle(45'100));
  EXPECT_FALSE(settle(44'000));  // not yet 2 °C inside
  EXPECT_TRUE(settle(43'000));
  EXPECT_FALSE(settle(-100));
  EXPECT_FALSE(settle(1'500));
  EXPECT_TRUE(settle(2'000));
  EXPECT_EQ(r.charger_enables, (std::vector<bool>{true, false, true, false, true}));
}

TEST(BoardEcho, EchoIsBuiltAfterTheCommandTookEffect) {
  Rig r;
  r.boot();
  r.send(C::Jog, 2, C::SetAccel, 30000, subs_of(xy_codec::SubscriberId::Param, static_cast<std::uint8_t>(xy_storage::ParamId::MaxAcceleration)));
  EXPECT_TRUE(r.tx.empty());  // nothing is answered from the interrupt
  r.tick();
  ASSERT_EQ(r.tx.size(), 1U);
  const auto e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->seq, r.seq);
  EXPECT_EQ(e->x.status, S::Accelerating);  // the jog already started in this cycle
  EXPECT_GT(r.ax(Axis::X).v, 0);  // DIR set this tick, first STEP the next (setup time)
  EXPECT_EQ(e->subs[0].data, 30000);  // the parameter written this cycle, read back
  EXPECT_EQ(r.board->main_state(), MainState::ParamSet);
  r.tick();
  EXPECT_EQ(r.board->main_state(), MainState::UserControl);
  EXPECT_EQ(r.tx.size(), 1U);  // one echo per command
}

TEST(BoardBlock, ChargerBlocksWithDecelerationAndUnblockClearsTargets) {
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 2, 400);
  const std::int32_t v_top = r.ax(Axis::X).v;
  ASSERT_GT(v_top, 0);
  r.in.charger = true;
  std::int32_t prev_v = v_top;
  bool stopped = false;
  for (int t = 0; t < 2000; ++t) {
    if (t % 100 == 0) r.send(C::Jog, 2);  // the PC keeps asking: must not matter
    r.tick();
    const auto& s = r.ax(Axis::X);
    EXPECT_LE(s.v, prev_v);  // brakes, never speeds up
    EXPECT_LE(prev_v - s.v, r.board->axis_config(Axis::X).accel + r.board->axis_config(Axis::X).v_start * xy_axis::kSpeedScale);
    if (stopped) {
      EXPECT_EQ(r.motor[0].steps, 0);
    }
    stopped = stopped || s.v == 0;
    prev_v = s.v;
  }
  EXPECT_TRUE(stopped);
  EXPECT_EQ(r.board->main_state(), MainState::Blocked);
  EXPECT_EQ(r.board->block(), Block::Charger);
  ASSERT_TRUE(r.last_echo().has_value());
  EXPECT_EQ(r.last_echo()->x.status, S::BlockedCharger);
  EXPECT_GT(r.board->counters().blocked_frames, 0U);

  r.in.charger = false;
  r.tick(50);
  EXPECT_EQ(r.board->main_state(), MainState::UserControl);
  EXPECT_EQ(r.ax(Axis::X).mode, xy_axis::Mode::Idle);
  EXPECT_EQ(r.ax(Axis::X).target, r.ax(Axis::X).pos);
  const std::int64_t at = r.steps_total[0];
  r.tick(500);  // G16: nothing resumes on its own
  EXPECT_EQ(r.steps_total[0], at);
  jog_for(r, Axis::X, 1, 100);  // a new command moves again
  EXPECT_GT(r.steps_total[0], at);
}

TEST(BoardBlock, UsbAndLowBatteryAgainstTheStoredThresholdWithHysteresis) {
  Rig r;
  r.boot();
  const std::uint16_t th = r.board->store().current().low_battery_mv;
  r.in.usb = true;
  r.tick();
  EXPECT_EQ(r.board->block(), Block::Usb);
  r.in.usb = false;
  r.in.battery_mv = static_cast<std::uint16_t>(th - 1);
  r.tick();
  EXPECT_EQ(r.board->block(), Block::Battery);
  r.in.battery_mv = th;
  r.tick();
  EXPECT_EQ(r.board->block(), Block::Battery);  // within the hysteresis
  r.in.battery_mv = static_cast<std::uint16_t>(th + kBatteryHysteresisMv);
  r.tick();
  EXPECT_EQ(r.board->block(), Block::None);
  r.in.battery_mv = th;
  r.tick();
  EXPECT_EQ(r.board->block(), Block::None);
  // Jog refused while blocked: no step at all.
  r.in.battery_mv = static_cast<std::uint16_t>(th - 1);
  jog_for(r, Axis::Y, -2, 300);
  EXPECT_EQ(r.steps_total[1], 0);
  EXPECT_EQ(r.last_echo()->y.status, S::BlockedBattery);
}

TEST(BoardSession, OnlyDataSessionOpenAcceptsCommands) {
  for (const auto& pins : {std::pair{true, true}, std::pair{true, false}, std::pair{false, false}}) {
    Rig r;
    r.boot();
    r.in.ble_status1 = pins.first;
    r.in.ble_status2 = pins.second;
    jog_for(r, Axis::X, 2, 300);
    EXPECT_EQ(r.steps_total[0], 0);
    EXPECT_TRUE(r.tx.empty());
    EXPECT_EQ(r.board->counters().gated_frames, 3U);
    EXPECT_EQ(r.board->counters().dispatched_frames, 0U);
    EXPECT_FALSE(r.board->session_open());
  }
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 2, 300);
  EXPECT_GT(r.steps_total[0], 0);
  // Session lost mid-jog (G15): the jog ends with a ramped stop.
  r.in.ble_status2 = false;
  const std::int32_t v = r.ax(Axis::X).v;
  ASSERT_GT(v, 0);
  r.tick();
  EXPECT_NE(r.ax(Axis::X).mode, xy_axis::Mode::Jog);
  EXPECT_LT(r.ax(Axis::X).v, v);
  EXPECT_GT(r.ax(Axis::X).v, 0);  // decelerating, not an emergency stop
}

TEST(BoardWatchdog, SilenceStopsAJogWithDecelerationAndMalformedFramesDoNotRefresh) {
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 2, 300);
  ASSERT_EQ(r.ax(Axis::X).mode, xy_axis::Mode::Jog);
  // 100 ms keep-alives hold the jog...
  jog_for(r, Axis::X, 2, 1000);
  EXPECT_EQ(r.ax(Axis::X).mode, xy_axis::Mode::Jog);
  // ...corrupted ones do not.
  auto bad = Rig::bytes_of(Rig::frame_of(++r.seq, C::Jog, 2, C::Nop, 0));
  bad[xy_codec::kCommandCrcOffset] = bad[xy_codec::kCommandCrcOffset] == 'A' ? 'B' : 'A';
  r.send(C::Jog, 2);
  r.tick();
  int t = 0;  // ticks since the tick of the last valid frame
  while (t < 1000 && r.ax(Axis::X).mode == xy_axis::Mode::Jog) {
    if (t % 50 == 0) r.send_raw(bad);
    r.tick();
    ++t;
  }
  // docs/board.md, link watchdog (G15): 300 ticks (3 x 100 ms) without a dispatched frame,
  // not one tick less or more; the rejected frames in between count for nothing.
  EXPECT_EQ(t, 300);
  EXPECT_EQ(r.board->counters().watchdog_expiries, 1U);
  const std::int32_t v = r.ax(Axis::X).v;
  EXPECT_GT(v, 0);  // ramped stop: still moving right after the expiry
  r.tick(2000);
  EXPECT_EQ(r.ax(Axis::X).v, 0);
  r.send(C::Nop, 0);
  r.tick();
  EXPECT_EQ(r.last_echo()->x.status, S::LinkLost);
}

TEST(BoardMalformed, RejectedFrameChangesOnlyCountersAndGetsATypedEcho) {
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 1, 150);
  const auto before_params = r.board->store().current();
  const auto seq = r.board->last_seq();
  const auto k0 = r.board->counters();
  auto bad = Rig::bytes_of(Rig::frame_of(++r.seq, C::Goto, 5000, C::Jog, 2));
  bad[xy_codec::kCommandCrcOffset + 3] = bad[xy_codec::kCommandCrcOffset + 3] == '0' ? '1' : '0';
  r.send_raw(bad);
  // Compare against an identical board that did not get the frame.
  Rig twin;
  twin.boot();
  jog_for(twin, Axis::X, 1, 150);
  r.tick();
  twin.tick();
  const auto e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->x.status, S::FrameRejected);
  EXPECT_EQ(e->x.data, static_cast<std::int32_t>(xy_codec::FrameError::BadCrc) * 100 + 36);
  EXPECT_EQ(e->seq, seq);
  EXPECT_EQ(r.board->last_seq(), seq);
  EXPECT_EQ(r.ax(Axis::X).pos, twin.ax(Axis::X).pos);
  EXPECT_EQ(r.ax(Axis::X).v, twin.ax(Axis::X).v);
  EXPECT_EQ(r.ax(Axis::Y).mode, xy_axis::Mode::Idle);
  EXPECT_EQ(r.board->store().current(), before_params);
  const auto k1 = r.board->counters();
  EXPECT_EQ(k1.framer.rejected_frames, k0.framer.rejected_frames + 1);
  EXPECT_EQ(k1.dispatched_frames, k0.dispatched_frames);
}

TEST(BoardParams, SaveRebootReloadAndConvertedToMicrosteps) {
  Rig r;
  r.boot();
  r.send(C::SetAccel, 40000);
  r.tick();
  r.send(C::SetFastSpeed, 12000);
  r.tick();
  EXPECT_EQ(r.board->store().current().max_acceleration_um_s2, 40000U);
  // 40000 um/s^2 at 2 mm pitch, 200 x 16: 64000 usteps/s^2.
  EXPECT_EQ(r.board->axis_config(Axis::Y).accel, 64000);
  EXPECT_EQ(r.board->axis_config(Axis::X).v_fast, 19200);
  const BootResult b = r.boot();  // reboot on the same FRAM
  EXPECT_FALSE(b.store.defaults_used());
  EXPECT_EQ(r.board->store().current().max_acceleration_um_s2, 40000U);
  EXPECT_EQ(r.board->store().current().fast_speed_um_s, 12000U);
  EXPECT_EQ(r.board->axis_config(Axis::X).accel, 64000);
}

TEST(BoardParams, InvalidParameterIsRefusedAndNothingIsWritten) {
  Rig r;
  r.boot();
  const auto seq = r.board->store().sequence();
  r.send(C::SetSlowSpeed, 20000);  // above the fast speed: breaks the speed order
  r.tick();
  EXPECT_EQ(r.last_echo()->x.status, S::CommandRefused);
  EXPECT_EQ(r.last_echo()->x.data, static_cast<std::int32_t>(C::SetSlowSpeed));
  r.send(C::SetMicrosteps, 3);  // not a power of two
  r.tick();
  EXPECT_EQ(r.last_echo()->x.status, S::CommandRefused);
  EXPECT_EQ(r.board->store().sequence(), seq);
  EXPECT_EQ(r.board->store().current(), xy_storage::defaults());
}

// docs/storage.md "Factory and user parameters": homing_mode 1 (towards the min endstop) is the
// only mode built; 0 (no homing) and 2 (StallGuard) refuse `home` with a typed refusal.
TEST(BoardParams, OnlyHomingModeOneHomes) {
  for (const int mode : {0, 1, 2}) {
    Rig r;
    {
      xy_storage::ParameterStore store(r.fram.bus());
      (void)store.boot();
      ASSERT_TRUE(store.set_parameter(static_cast<std::uint8_t>(xy_storage::ParamId::HomingMode), mode).ok());
    }
    r.in.endstop_min[0] = 1;
    r.boot();
    r.send(C::Home, 0);
    r.tick();
    if (mode == 1) {
      EXPECT_EQ(r.ax(Axis::X).homed, 1);
      EXPECT_NE(r.last_echo()->x.status, S::CommandRefused);
    } else {
      EXPECT_EQ(r.last_echo()->x.status, S::CommandRefused) << mode;
      EXPECT_EQ(r.last_echo()->x.data, static_cast<std::int32_t>(C::Home)) << mode;
      EXPECT_EQ(r.ax(Axis::X).homed, 0) << mode;
    }
  }
}

TEST(BoardParams, MotionParametersOnlyAtRestCurrentsAnytime) {
  Rig r;
  r.boot();
  r.send(C::Jog, 2);
  r.tick(50);
  ASSERT_GT(r.ax(Axis::X).v, 0);
  r.send(C::Nop, 0, C::SetAccel, 1);  // would leave the moving X axis almost without brakes
  r.tick();
  EXPECT_EQ(r.last_echo()->y.status, S::CommandRefused);
  EXPECT_EQ(r.board->axis_config(Axis::X).accel, 32000);
  EXPECT_EQ(r.board->store().current(), xy_storage::defaults());
  r.send(C::SetIrun, 20);
  r.tick();
  EXPECT_EQ(r.board->store().current().run_current_cs, 20);
  r.send(C::Stop, 0);
  r.tick(1000);
  r.send(C::SetAccel, 1);
  r.tick();
  EXPECT_EQ(r.board->axis_config(Axis::X).accel, 2);
}

TEST(BoardParams, StorageFaultShowsInTheEchoAndKeepsThePreviousSet) {
  Rig r;
  r.boot();
  // Both copies' first byte stuck: every verify fails.
  for (const auto base : xy_storage::kCopyBase) r.fram.stick_bits(base, 0xFF, 0x5A);
  r.send(C::SetAccel, 30000);
  r.tick();
  const auto e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->x.status, S::Fault);
  EXPECT_EQ(e->x.data, kFaultStorage + static_cast<std::int32_t>(xy_storage::StoreStatus::StorageFault));
  EXPECT_EQ(r.board->store().current().max_acceleration_um_s2, xy_storage::defaults().max_acceleration_um_s2);
  EXPECT_EQ(r.board->axis_config(Axis::X).accel, 32000);
  r.fram.clear_faults();
  r.send(C::ClearFault, 0);
  r.tick();
  EXPECT_EQ(r.last_echo()->x.status, S::Idle);
}

TEST(BoardDriver, IrunIholdChangeReachesBothChipsAndSurvivesAChipReset) {
  Rig r;
  r.boot();
  r.send(C::SetIrun, 22, C::SetIhold, 5);
  r.tick();
  for (auto& chip : r.tmc) {
    const std::uint32_t w = chip.chip_register(tmc::Reg::IHOLD_IRUN);
    EXPECT_EQ(tmc::field_get(w, tmc::Field::IHOLD_IRUN_IRUN), 22);
    EXPECT_EQ(tmc::field_get(w, tmc::Field::IHOLD_IRUN_IHOLD), 5);
  }
  r.tmc[1].power_cycle();
  EXPECT_EQ(r.tmc[1].chip_register(tmc::Reg::IHOLD_IRUN), 0U);
  r.tick(static_cast<int>(kDriverCheckPeriod));
  EXPECT_EQ(tmc::field_get(r.tmc[1].chip_register(tmc::Reg::IHOLD_IRUN), tmc::Field::IHOLD_IRUN_IRUN), 22);
  r.boot();  // and after a reboot from FRAM
  EXPECT_EQ(tmc::field_get(r.tmc[0].chip_register(tmc::Reg::IHOLD_IRUN), tmc::Field::IHOLD_IRUN_IRUN), 22);
}

TEST(BoardEndstop, HitStopsAtOnceAndRefusesFurtherMotionTowardIt) {
  Rig r;
  r.boot();
  jog_for(r, Axis::Y, 2, 300);
  ASSERT_GT(r.ax(Axis::Y).v, 0);
  r.in.endstop_max[1] = 1;
  r.tick();
  EXPECT_EQ(r.ax(Axis::Y).v, 0);
  EXPECT_EQ(r.motor[1].steps, 0);
  const std::int64_t at = r.steps_total[1];
  jog_for(r, Axis::Y, 2, 300);
  EXPECT_EQ(r.steps_total[1], at);
  EXPECT_EQ(r.last_echo()->y.status, S::CommandRefused);
  jog_for(r, Axis::Y, -1, 300);  // away from it is allowed
  EXPECT_LT(r.steps_total[1], at);
  r.send(C::Stop, 0, C::Stop, 0);
  r.tick();
  EXPECT_EQ(r.last_echo()->y.status, S::Decelerating);
  r.tick(500);
  r.send(C::Nop, 0, C::Nop, 0);
  r.tick();
  EXPECT_EQ(r.last_echo()->y.status, S::StoppedByUser);
}

// docs/board.md "Echo content": REACHED is standing at the target. A switch that halts a move
// on the move's own target ended nothing the move did not reach (docs/echo-model.md, found by
// the board fuzz target): here a goto to the current position given in the very tick the max
// switch turns on under a carriage creeping up at its start speed, still on step 0.
TEST(BoardEndstop, HaltOnTheMovesOwnTargetIsReached) {
  Rig r;
  r.boot();
  ASSERT_EQ(r.board->shutdown(), ShutdownResult::Ok);  // a valid step counter: the position is known
  r.boot();
  ASSERT_EQ(r.ax(Axis::Y).homed, 1);
  r.send(C::Nop, 0, C::Jog, 1);
  r.tick();
  ASSERT_GT(r.ax(Axis::Y).v, 0);
  ASSERT_EQ(r.ax(Axis::Y).pos, 0);
  r.in.endstop_max[1] = 1;
  r.send(C::Nop, 0, C::Goto, 0);
  r.tick();
  EXPECT_EQ(r.ax(Axis::Y).v, 0);
  EXPECT_EQ(r.ax(Axis::Y).latch_max, 1);
  EXPECT_EQ(r.last_echo()->y.status, S::TargetReached);
  EXPECT_EQ(r.last_echo()->y.data, 0);
}

// docs/motion.md §4 (G8): a latch clears only after a step away with the input released. A
// switch active at power-up is the carriage resting on it: released by a bounce, it must still
// refuse motion toward it (found by the board fuzz target).
TEST(BoardEndstop, ActiveAtPowerUpIsLatchedUntilTheCarriageStepsAway) {
  Rig r;
  r.in.endstop_max[1] = 1;
  r.boot();
  r.in.endstop_max[1] = 0;  // the Hall switch bounces open
  r.tick();
  const std::int64_t at = r.steps_total[1];
  jog_for(r, Axis::Y, 2, 300);
  EXPECT_EQ(r.steps_total[1], at) << "stepped toward the switch it was resting on at power-up";
  EXPECT_EQ(r.last_echo()->y.status, S::CommandRefused);
  jog_for(r, Axis::Y, -1, 300);  // away from it is allowed, and clears the latch
  EXPECT_LT(r.steps_total[1], at);
  r.send(C::Stop, 0, C::Stop, 0);
  r.tick(500);
  const std::int64_t away = r.steps_total[1];
  jog_for(r, Axis::Y, 1, 300);
  EXPECT_GT(r.steps_total[1], away) << "the latch must clear once the carriage stepped away";
}

TEST(BoardStepCounter, ValidOnlyAfterOrderlyShutdownAndClearedBeforeMotion) {
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 2, 300);
  r.send(C::Stop, 0);
  r.tick(1000);
  const std::int32_t pos = r.ax(Axis::X).pos;
  ASSERT_NE(pos, 0);
  EXPECT_EQ(r.board->shutdown(), ShutdownResult::Ok);
  EXPECT_TRUE(r.board->store().current().step_counts_valid);
  const BootResult b = r.boot();
  EXPECT_EQ(b.start[0].homed, 1);
  EXPECT_EQ(r.ax(Axis::X).pos, pos);
  EXPECT_TRUE(r.board->store().current().step_counts_valid);
  r.send(C::Jog, 1);
  r.tick();
  EXPECT_GT(r.ax(Axis::X).v, 0);
  EXPECT_FALSE(r.board->store().current().step_counts_valid);
  r.boot();  // a crash (no shutdown) now: the counter is not trusted
  EXPECT_EQ(r.ax(Axis::X).homed, 0);
}

TEST(BoardStepCounter, ShutdownRefusedWhileMoving) {
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 2, 200);
  EXPECT_EQ(r.board->shutdown(), ShutdownResult::Moving);
  EXPECT_FALSE(r.board->store().current().step_counts_valid);
}

TEST(BoardSleep, PeripheralsOffRefusesMotionAndDisablesDrivers) {
  Rig r;
  r.boot();
  jog_for(r, Axis::X, 2, 200);
  r.send(C::PeriphOff, 0);
  r.tick(1500);
  EXPECT_EQ(r.ax(Axis::X).v, 0);
  EXPECT_FALSE(r.motor[0].enable);
  const std::int64_t at = r.steps_total[0];
  jog_for(r, Axis::X, 2, 300);
  EXPECT_EQ(r.steps_total[0], at);
  EXPECT_EQ(r.last_echo()->x.status, S::CommandRefused);
  r.send(C::PeriphOn, 0);
  r.tick();
  EXPECT_TRUE(r.motor[0].enable);
  jog_for(r, Axis::X, 2, 300);
  EXPECT_GT(r.steps_total[0], at);
}

TEST(BoardCallbackTable, BoundCheckRejectsTheFirstIdPastTheTable) {
  xy_frame::CallbackTable t;
  const xy_frame::Handler h = [](void*, xy_frame::Axis, std::int32_t) { return xy_frame::HandlerStatus::Done; };
  EXPECT_FALSE(t.install(xy_frame::CallbackTable::kSize, h));
  EXPECT_EQ(t.find(xy_frame::CallbackTable::kSize), nullptr);
  EXPECT_TRUE(t.install(xy_frame::CallbackTable::kSize - 1, h));
}

TEST(BoardEncoder, StartPositionFromTheEncoderWinsOverTheSavedCounter) {
  Rig r;
  r.in.encoder[1] = {2, 8192, 1};  // 2.5 revolutions
  r.boot();
  EXPECT_EQ(r.ax(Axis::Y).homed, 1);
  EXPECT_EQ(r.ax(Axis::Y).pos, 8000);  // 2.5 x 3200 usteps
  EXPECT_EQ(r.board->position_um(Axis::Y), 5000);
}
