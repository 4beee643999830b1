// The board core under hardware faults and bad stored parameters: a stored set that passes
// its checks but does not convert runs the board on the defaults with a BadParams fault;
// a TMC2130 whose SPI fails (at boot or later, caught by the periodic GSTAT check) and an
// FRAM whose SPI fails (save, shutdown, the step-counter clear before motion) are typed
// faults in the echo and move nothing; the receive ring drops and counts what overflows it;
// subscriber values at their edges.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "core/xy/storage/store.hpp"
#include "core/xy/tmc2130/result.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
using C = xy_codec::CommandId;
using S = xy_codec::EchoStatus;
namespace chip = ap::xy_tmc2130;

namespace {

// SPI wrappers that can go dead (the HAL reports every transfer as failed).
struct FlakyTmc {
  model::xy_tmc2130::Device* dev;
  bool dead = false;
  static bool spi(void* ctx, const chip::Datagram& tx, chip::Datagram& rx) {
    auto* self = static_cast<FlakyTmc*>(ctx);
    if (self->dead) return false;
    rx = self->dev->transfer(tx);
    return true;
  }
};

struct FlakyFram {
  model::Mb85rs256b* chip;
  bool dead = false;
  static bool transfer(void* ctx, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
    auto* self = static_cast<FlakyFram*>(ctx);
    if (self->dead) return false;
    return self->chip->transfer(tx, rx);
  }
};

struct FaultyRig {
  Rig rig;
  std::array<FlakyTmc, kAxes> tmc{FlakyTmc{&rig.tmc[0]}, FlakyTmc{&rig.tmc[1]}};
  FlakyFram fram{&rig.fram};

  BootResult boot() {
    Hardware hw = rig.hardware();
    for (std::size_t i = 0; i < kAxes; ++i) hw.tmc[i] = chip::SpiPort{&FlakyTmc::spi, &tmc[i]};
    hw.fram = xy_storage::SpiBus{&FlakyFram::transfer, &fram};
    rig.board = std::make_unique<Board>(hw);
    return rig.board->boot();
  }
  xy_frame::EchoFrame nop(xy_frame::SubscriberSlots subs = {}) {
    rig.send(C::Nop, 0, C::Nop, 0, subs);
    rig.tick();
    const auto e = rig.last_echo();
    EXPECT_TRUE(e.has_value());
    return e.value_or(xy_frame::EchoFrame{});
  }
};

constexpr std::int32_t kBusFailure = static_cast<std::int32_t>(chip::Error::BusFailure);
constexpr std::int32_t kStorageFault = static_cast<std::int32_t>(xy_storage::StoreStatus::StorageFault);

// A fine drive: 100 um pitch, 1000 steps x 256 microsteps = 2560 usteps/um, so the step
// generator's 1e6 usteps/s is only 390 um/s and 1e7 usteps/s2 only 3906 um/s2.
xy_storage::ParameterSet fine_set() {
  xy_storage::ParameterSet s = xy_storage::defaults();
  s.lead_pitch_um = 100;
  s.steps_per_rev = 1000;
  s.microsteps = 256;
  s.start_speed_um_s = 100;
  s.slow_speed_um_s = 200;
  s.fast_speed_um_s = 300;
  s.homing_speed_um_s = 300;
  s.max_acceleration_um_s2 = 1000;
  return s;
}

}  // namespace

TEST(BoardFaults, DeriveRefusesSetsThatDoNotConvert) {
  ASSERT_TRUE(derive(xy_storage::defaults()).ok);
  const xy_storage::ParameterSet base = fine_set();
  ASSERT_TRUE(xy_storage::validate(base).ok());
  ASSERT_TRUE(derive(base).ok);

  xy_storage::ParameterSet invalid = base;
  invalid.start_speed_um_s = invalid.slow_speed_um_s + 1;   // fails validate (speed order)
  EXPECT_FALSE(derive(invalid).ok);

  struct Variant {
    const char* what;
    void (*edit)(xy_storage::ParameterSet&);
  };
  const std::vector<Variant> variants{
      {"start speed", [](xy_storage::ParameterSet& s) {
         s.start_speed_um_s = s.slow_speed_um_s = s.fast_speed_um_s = s.homing_speed_um_s = 400;
       }},
      {"slow speed", [](xy_storage::ParameterSet& s) { s.slow_speed_um_s = s.fast_speed_um_s = s.homing_speed_um_s = 400; }},
      {"fast speed", [](xy_storage::ParameterSet& s) { s.fast_speed_um_s = 400; }},
      {"acceleration", [](xy_storage::ParameterSet& s) { s.max_acceleration_um_s2 = 5000; }},
      {"x travel limit", [](xy_storage::ParameterSet& s) { s.soft_max_x_um = 999'999; }},
      {"y home offset", [](xy_storage::ParameterSet& s) { s.home_offset_y_um = 999'999; }},
  };
  for (const Variant& v : variants) {
    xy_storage::ParameterSet s = base;
    v.edit(s);
    ASSERT_TRUE(xy_storage::validate(s).ok()) << v.what;
    EXPECT_FALSE(derive(s).ok) << v.what << " beyond the step generator's range";
  }
}

TEST(BoardFaults, StoredSetThatDoesNotConvertRunsOnDefaults) {
  FaultyRig f;
  xy_storage::ParameterSet stored = fine_set();
  stored.fast_speed_um_s = 400;
  {
    xy_storage::ParameterStore writer(f.rig.fram.bus());
    (void)writer.boot();
    ASSERT_TRUE(writer.save(stored).ok());
  }
  const BootResult b = f.boot();
  EXPECT_FALSE(b.store.defaults_used()) << "the set itself loads: CRC and ranges are fine";
  EXPECT_TRUE(b.drivers_ok);
  const Derived d = derive(xy_storage::defaults());
  EXPECT_EQ(f.rig.board->axis_config(Axis::X).v_fast, d.cfg[0].v_fast);
  EXPECT_EQ(f.rig.board->mechanics().pitch_um, d.mech.pitch_um);
  const xy_frame::EchoFrame e = f.nop();
  EXPECT_EQ(e.x.status, S::Fault);
  EXPECT_EQ(e.x.data, kFaultBadParams);
  f.rig.send(C::ClearFault, 0);
  f.rig.tick();
  EXPECT_EQ(f.rig.last_echo()->x.status, S::Idle);
}

TEST(BoardFaults, DriverBusFailureAtBootIsAFaultOfThatAxis) {
  for (const std::size_t dead : {std::size_t{0}, std::size_t{1}}) {
    SCOPED_TRACE(dead);
    FaultyRig f;
    f.tmc[dead].dead = true;
    const BootResult b = f.boot();
    EXPECT_FALSE(b.drivers_ok);
    const xy_frame::EchoFrame e = f.nop();
    EXPECT_EQ(e.x.status, S::Fault);
    EXPECT_EQ(e.x.data, (dead == 0 ? kFaultDriverX : kFaultDriverY) + kBusFailure);
    // The healthy chip still got its currents and microsteps.
    const auto& ok_chip = f.rig.tmc[1 - dead];
    EXPECT_EQ(chip::field_get(ok_chip.chip_register(chip::Reg::IHOLD_IRUN), chip::Field::IHOLD_IRUN_IRUN),
              xy_storage::defaults().run_current_cs);
    EXPECT_EQ(chip::field_get(ok_chip.chip_register(chip::Reg::CHOPCONF), chip::Field::CHOPCONF_MRES), 4);
  }
}

TEST(BoardFaults, DriverLostAfterBootIsCaughtByThePeriodicCheck) {
  FaultyRig f;
  ASSERT_TRUE(f.boot().drivers_ok);
  xy_frame::SubscriberSlots subs{};
  subs[0] = {xy_codec::SubscriberId::DrvStatusLo, 0};
  subs[1] = {xy_codec::SubscriberId::DrvStatusHi, 1};
  xy_frame::EchoFrame e = f.nop(subs);
  ASSERT_EQ(e.x.status, S::Idle);
  // DRV_STATUS bits 31..16 at rest after boot: stst, CS_ACTUAL = IHOLD 8 (docs/tmc2130.md
  // "Boot configuration"; the model's standstill current).
  EXPECT_EQ(e.subs[1].data, 0x8008);

  f.tmc[1].dead = true;
  f.rig.tick(static_cast<int>(kDriverCheckPeriod));
  e = f.nop(subs);
  EXPECT_EQ(e.x.status, S::Fault);
  EXPECT_EQ(e.x.data, kFaultDriverY + kBusFailure);
  EXPECT_EQ(e.subs[1].data, 0) << "an unreadable DRV_STATUS reads as 0";
  EXPECT_EQ(e.subs[0].data, 0) << "X: DRV_STATUS bits 15..0 of the reset value";
}

TEST(BoardFaults, FramBusFailureFaultsSaveAndShutdownAndMovesNothing) {
  FaultyRig f;
  f.boot();
  // An orderly shutdown makes the saved step counter valid; after the reboot the first
  // motion must clear that flag in FRAM first.
  ASSERT_EQ(f.rig.board->shutdown(), ShutdownResult::Ok);
  f.boot();
  ASSERT_TRUE(f.rig.board->store().current().step_counts_valid);
  ASSERT_EQ(f.rig.ax(Axis::X).homed, 1);

  f.fram.dead = true;
  f.rig.send(C::Goto, 1000);
  f.rig.tick(20);
  EXPECT_EQ(f.rig.ax(Axis::X).v, 0);
  EXPECT_EQ(f.rig.ax(Axis::X).pos, 0);
  EXPECT_EQ(f.rig.steps_total[0], 0);
  xy_frame::EchoFrame e = f.nop();
  EXPECT_EQ(e.x.status, S::Fault);
  EXPECT_EQ(e.x.data, kFaultStorage + kStorageFault);
  EXPECT_TRUE(f.rig.board->store().current().step_counts_valid) << "the flag was never cleared";

  f.rig.send(C::ClearFault, 0);
  f.rig.tick();
  f.rig.send(C::SaveParams, 0);
  f.rig.tick();
  e = *f.rig.last_echo();
  EXPECT_EQ(e.x.status, S::Fault);
  EXPECT_EQ(e.x.data, kFaultStorage + kStorageFault);

  f.rig.send(C::ClearFault, 0);
  f.rig.tick();
  EXPECT_EQ(f.rig.board->shutdown(), ShutdownResult::StorageFault);
  e = f.nop();
  EXPECT_EQ(e.x.status, S::Fault);
  EXPECT_EQ(e.x.data, kFaultStorage + kStorageFault);
}

TEST(BoardFaults, ReceiveRingDropsAndCountsOverflow) {
  Rig r;
  r.boot();
  std::vector<std::uint8_t> flood(kRxCapacity + 44, ' ');
  r.send_raw(flood);
  EXPECT_EQ(r.board->counters().rx_overruns, 44U);
  r.tick();
  r.send(C::Nop, 0);
  r.tick();
  ASSERT_TRUE(r.last_echo().has_value()) << "the ring recovers once drained";
}

TEST(BoardFaults, WithoutAnInputCallbackTheBoardRunsOnDefaultInputs) {
  Rig r;
  Hardware hw = r.hardware();
  hw.sample = nullptr;
  r.board = std::make_unique<Board>(hw);
  const BootResult b = r.board->boot();
  EXPECT_TRUE(b.drivers_ok);
  EXPECT_EQ(b.start[0].error, xy_axis::Error::NotHomed);
  r.send(C::Nop, 0);
  r.tick();
  ASSERT_TRUE(r.last_echo().has_value());
  EXPECT_EQ(r.board->main_state(), MainState::UserControl);
}

TEST(BoardFaults, SubscriberValuesAtTheirEdges) {
  Rig r;
  r.in.encoder[1] = xy_axis::EncoderReading{0, 16384, 1};   // out-of-range count: no position
  r.in.encoder[0] = xy_axis::EncoderReading{1, 0, 1};       // one turn = one pitch
  r.boot();
  r.send_raw(std::vector<std::uint8_t>{'x', 'y'});   // two rejected bytes before a frame
  xy_frame::SubscriberSlots subs{};
  subs[0] = {xy_codec::SubscriberId::EncoderUm, 1};
  subs[1] = {xy_codec::SubscriberId::EncoderUm, 0};
  subs[2] = {xy_codec::SubscriberId::Param, 99};   // beyond the parameter table
  subs[3] = {xy_codec::SubscriberId::LinkStats, 2};
  r.send(C::Nop, 0, C::Nop, 0, subs);
  r.tick();
  auto e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->subs[0].data, 0);
  EXPECT_EQ(e->subs[1].data, static_cast<std::int32_t>(xy_storage::defaults().lead_pitch_um));
  EXPECT_EQ(e->subs[2].data, 0);
  EXPECT_EQ(e->subs[3].data, 2) << "the two stray bytes were rejected";
  subs = {};
  for (std::uint8_t k = 0; k < 4; ++k) subs[k] = {xy_codec::SubscriberId::LinkStats, k};
  r.send(C::Nop, 0, C::Nop, 0, subs);
  r.tick();
  e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->subs[0].data, 2) << "accepted frames";
  EXPECT_EQ(e->subs[1].data, 0) << "rejected frames: stray bytes are not a frame";
  EXPECT_EQ(e->subs[2].data, 2) << "rejected bytes";
  EXPECT_EQ(e->subs[3].data, 0) << "no watchdog expiry yet";
}

TEST(BoardFaults, MetaItemsAreNotParameters) {
  Rig r;
  r.boot();
  xy_frame::SubscriberSlots subs{};
  subs[0] = {xy_codec::SubscriberId::Param, static_cast<std::uint8_t>(xy_storage::ParamId::Sequence)};
  subs[1] = {xy_codec::SubscriberId::Param, static_cast<std::uint8_t>(xy_storage::ParamId::LowBatteryMv)};
  r.send(C::Nop, 0, C::Nop, 0, subs);
  r.tick();
  const auto e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->subs[0].data, 0);
  EXPECT_EQ(e->subs[1].data, static_cast<std::int32_t>(xy_storage::defaults().low_battery_mv));
}

// New mechanics convert every position; one that no longer fits the position range leaves
// that axis unhomed (it must home again) instead of wrapping, the other keeps its place.
TEST(BoardFaults, MechanicsChangeUnhomesAnAxisWhosePositionNoLongerFits) {
  Rig r;
  r.in.encoder[0] = xy_axis::EncoderReading{312'500, 0, 1};   // 312500 rev x 3200 = kPosMax usteps
  r.in.encoder[1] = xy_axis::EncoderReading{1, 0, 1};
  r.boot();
  ASSERT_EQ(r.ax(Axis::X).pos, xy_axis::kPosMax);
  ASSERT_EQ(r.ax(Axis::X).homed, 1);
  ASSERT_EQ(r.ax(Axis::Y).pos, 3200);
  r.send(C::SetMicrosteps, 256);
  r.tick();
  EXPECT_EQ(r.board->mechanics().microsteps, 256);
  EXPECT_EQ(r.ax(Axis::X).homed, 0);
  EXPECT_EQ(r.ax(Axis::Y).homed, 1);
  EXPECT_EQ(r.ax(Axis::Y).pos, 3200 * 16);   // the same 2 mm in 16x finer steps
}

// On a fine drive (2560 usteps/um) the largest relative move the wire allows does not fit the
// position range: refused with the command's ID, nothing moves.
TEST(BoardFaults, MoveBeyondThePositionRangeIsRefused) {
  FaultyRig f;
  {
    xy_storage::ParameterStore writer(f.rig.fram.bus());
    (void)writer.boot();
    ASSERT_TRUE(writer.save(fine_set()).ok());
  }
  f.boot();
  ASSERT_EQ(f.rig.board->mechanics().pitch_um, 100);
  f.rig.send(C::Move, 999'999);
  f.rig.tick();
  const auto e = f.rig.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->x.status, S::CommandRefused);
  EXPECT_EQ(e->x.data, static_cast<std::int32_t>(C::Move));
  f.rig.tick(10);
  EXPECT_EQ(f.rig.steps_total[0], 0);
}
