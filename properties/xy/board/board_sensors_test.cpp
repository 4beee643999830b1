// The board's I2C sensors (docs/sensors.md "On the board"): the TMP117 read once per 250 ms
// conversion and the ICM-20789 every tick, the integrated angle, the wire clamp of the
// temperature subscriber, every branch of the error policy (keep the last good value, latch
// after 3 periods / 10 ticks, retry once a second / every 100 ms, a foreign part never
// written), a board without a sensor bus, and motion never touched by any of it.
// Expected values are worked out from the datasheets and docs/protocol.md, written literally.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "sim/xy/rig/rig_sensors.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
using C = xy_codec::CommandId;
using S = xy_codec::EchoStatus;
using Sub = xy_codec::SubscriberId;

namespace {

constexpr std::uint8_t kTmp = 0x48;  // TMP117, ADD0 to GND (SNOSD82D Table 7-2)
constexpr std::uint8_t kImu = 0x68;  // ICM-20789, AD0 low (DS-000169 §11.2)

// Transactions in the bus log to `address` whose first byte (the register pointer) is `reg`.
unsigned count(const Rig& r, std::uint8_t address, std::uint8_t reg) {
  unsigned n = 0;
  for (const auto& t : r.i2c.log()) n += t.address == address && !t.tx.empty() && t.tx[0] == reg ? 1U : 0U;
  return n;
}
unsigned count_to(const Rig& r, std::uint8_t address) {
  unsigned n = 0;
  for (const auto& t : r.i2c.log()) n += t.address == address ? 1U : 0U;
  return n;
}

// The two subscriber values of an echo asked for in slots 0 and 1.
struct Subs {
  std::int32_t temperature = 0;
  std::int32_t rotation = 0;
  xy_frame::AxisEcho x{};
};
Subs ask(Rig& r) {
  xy_frame::SubscriberSlots s{};
  s[0] = {Sub::TemperatureMc, 0};
  s[1] = {Sub::RotationMdeg, 0};
  r.send(C::Nop, 0, C::Nop, 0, s);
  r.tick();
  const auto e = r.last_echo();
  EXPECT_TRUE(e.has_value());
  if (!e) return {};
  return {e->subs[0].data, e->subs[1].data, e->x};
}

struct Booted {
  Rig rig;
  Booted() { rig.boot(); }
};

// n rig ticks, counting the transactions to `address` that start with register `reg`.
unsigned ticks_counting(Rig& r, int n, std::uint8_t address, std::uint8_t reg) {
  unsigned c = 0;
  for (int i = 0; i < n; ++i) {
    r.tmp117.chip.advance_ms(1);
    r.board->tick();
    c += count(r, address, reg);
    r.i2c.clear_log();
  }
  return c;
}
unsigned ticks_counting_to(Rig& r, int n, std::uint8_t address) {
  unsigned c = 0;
  for (int i = 0; i < n; ++i) {
    r.tmp117.chip.advance_ms(1);
    r.board->tick();
    c += count_to(r, address);
    r.i2c.clear_log();
  }
  return c;
}

}  // namespace

TEST(BoardSensors, BootConfiguresBothAndReportsNoTemperatureUntilTheFirstConversion) {
  Booted b;
  EXPECT_EQ(b.rig.board->sensors().temperature, SensorState::Ok);
  EXPECT_EQ(b.rig.board->sensors().gyro, SensorState::Ok);
  EXPECT_EQ(b.rig.board->fault_code(), 0);
  // Temp_Result's reset value -256 °C until the first reading; the wire's floor is -99999.
  EXPECT_EQ(b.rig.board->temperature_mc(), -256000);
  EXPECT_FALSE(b.rig.board->sensors().temperature_valid);
  const Subs s = ask(b.rig);
  EXPECT_EQ(s.temperature, -99999);
  EXPECT_EQ(s.rotation, 0);
}

TEST(BoardSensors, TemperatureIsReadOncePerConversionPeriod) {
  Booted b;
  Rig& r = b.rig;
  // 23456 m°C: nearest code 23456 * 128 / 1000 = 3002.4 -> 3002 = 23453.125 m°C -> 23453.
  r.tmp117.chip.set_temperature_mc(23456);
  EXPECT_EQ(ticks_counting(r, 249, kTmp, 0x00), 0U);
  EXPECT_EQ(r.board->temperature_mc(), -256000);
  EXPECT_EQ(ticks_counting(r, 1, kTmp, 0x00), 1U);  // tick 250
  EXPECT_EQ(r.board->temperature_mc(), 23453);
  EXPECT_TRUE(r.board->sensors().temperature_valid);
  EXPECT_EQ(ticks_counting(r, 1000, kTmp, 0x00), 4U);
  EXPECT_EQ(ticks_counting(r, 1000, kImu, 0x47), 1000U);  // GYRO_ZOUT_H, every tick
}

TEST(BoardSensors, RotationIsTheExactIntegralOfOneSamplePerTick) {
  Booted b;
  // 90 °/s at 131 LSB/(°/s) is code 11790: 90 m° per 1 ms tick.
  b.rig.gyro.chip.set_rate_code(11790);
  b.rig.tick(1000);
  EXPECT_EQ(b.rig.board->rotation_mdeg(), 90000);
  // Code 1 is 1/131 m° per tick: 130 ticks stay below 1 m°, the 131st reaches it.
  b.rig.gyro.chip.set_rate_code(1);
  b.rig.tick(130);
  EXPECT_EQ(b.rig.board->rotation_mdeg(), 90000);
  b.rig.tick(1);
  EXPECT_EQ(b.rig.board->rotation_mdeg(), 90001);
  // Backwards through zero: the angle wraps to just below a full turn.
  b.rig.gyro.chip.set_rate_code(-11790);
  b.rig.tick(1000);
  EXPECT_EQ(b.rig.board->rotation_mdeg(), 1);
  b.rig.gyro.chip.set_rate_code(-131);
  b.rig.tick(2);
  EXPECT_EQ(b.rig.board->rotation_mdeg(), 359999);
  b.rig.gyro.chip.set_rate_code(0);
  EXPECT_EQ(ask(b.rig).rotation, 359999);
}

TEST(BoardSensors, TemperatureBelowTheWireFieldIsClampedNotWrapped) {
  Booted b;
  // -120 °C is code -15360 exactly (-120000 * 128 / 1000): far below -99.999 °C.
  b.rig.tmp117.chip.set_temperature_mc(-120000);
  b.rig.tick(250);
  EXPECT_EQ(b.rig.board->temperature_mc(), -120000);
  EXPECT_EQ(ask(b.rig).temperature, -99999);
  // The register's top, 0x7FFF = 255.9921875 °C -> 255992, fits the wire as it is.
  b.rig.tmp117.chip.set_temperature_mc(300000);
  b.rig.tick(249);
  EXPECT_EQ(b.rig.board->temperature_mc(), 255992);
  EXPECT_EQ(ask(b.rig).temperature, 255992);
  // Just inside the floor: -99.9921875 °C (code -12799) -> -99992 on the wire.
  b.rig.tmp117.chip.set_temperature_mc(-99992);
  b.rig.tick(249);
  EXPECT_EQ(b.rig.board->temperature_mc(), -99992);
  EXPECT_EQ(ask(b.rig).temperature, -99992);
}

TEST(BoardSensors, TemperatureKeepsTheLastGoodValueThenLatchesAfterThreeMissedPeriodsAndRetriesEverySecond) {
  Booted b;
  Rig& r = b.rig;
  r.tmp117.chip.set_temperature_mc(25000);
  r.tick(250);
  ASSERT_EQ(r.board->temperature_mc(), 25000);
  r.tmp117.present = false;
  r.tick(500);  // ticks 500 and 750: two misses, the last good value stays
  EXPECT_EQ(r.board->temperature_mc(), 25000);
  EXPECT_EQ(r.board->sensors().temperature_misses, 2U);
  EXPECT_EQ(r.board->fault_code(), 0);
  r.tick(250);  // tick 1000: the third, an address NACK (error 1)
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Lost);
  EXPECT_EQ(r.board->fault_code(), 5001);
  EXPECT_EQ(r.board->temperature_mc(), 25000);
  const Subs s = ask(r);
  EXPECT_EQ(s.x.status, S::Fault);
  EXPECT_EQ(s.x.data, 5001);
  EXPECT_EQ(s.temperature, 25000);
  // Lost: no reads, one configure() attempt per second (ticks 2000, 3000: Device_ID first).
  EXPECT_EQ(ticks_counting(r, 999, kTmp, 0x0F), 1U);  // ticks 1002..2000
  r.tmp117.present = true;
  r.tmp117.chip.set_temperature_mc(30000);
  EXPECT_EQ(ticks_counting(r, 1000, kTmp, 0x0F), 1U);  // tick 3000: back
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Ok);
  EXPECT_EQ(r.board->temperature_mc(), 25000);
  r.tick(250);  // tick 3250: read again
  EXPECT_EQ(r.board->temperature_mc(), 30000);
  // The fault stays latched until the PC clears it (docs/board.md G12).
  EXPECT_EQ(r.board->fault_code(), 5001);
  r.send(C::ClearFault, 0);
  r.tick();
  EXPECT_EQ(r.board->fault_code(), 0);
}

TEST(BoardSensors, NoConversionYetCountsAsAMissedPeriod) {
  Booted b;
  Rig& r = b.rig;
  // Temp_Result shows its reset code at each read (ticks 250, 500, 750): error 7.
  for (int k = 0; k < 3; ++k) {
    r.tick(249);
    r.tmp117.chip.set_result_code(0x8000);
    r.tick(1);
  }
  EXPECT_EQ(r.board->temperature_mc(), -256000);
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Lost);
  EXPECT_EQ(r.board->fault_code(), 5007);
}

TEST(BoardSensors, AForeignPartAtTheTemperatureAddressIsNeverWrittenNorRetried) {
  Rig r;
  r.tmp117.chip.set_device_id(0x0118);
  r.boot();
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Foreign);
  EXPECT_EQ(r.board->fault_code(), 5004);
  EXPECT_EQ(r.tmp117.chip.reg(ap::xy_tmp117::Reg::Configuration), 0x0220);  // power-up value kept
  r.i2c.clear_log();
  EXPECT_EQ(ticks_counting_to(r, 3000, kTmp), 0U);
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Ok);  // the other sensor is unaffected
}

TEST(BoardSensors, TemperatureConfigureFailingAtBootLatchesAndIsRetried) {
  Rig r;
  r.tmp117.present = false;
  r.boot();
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Lost);
  EXPECT_EQ(r.board->fault_code(), 5001);
  r.tmp117.present = true;
  r.tick(1000);
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Ok);
}

TEST(BoardSensors, AFailedGyroReadHoldsTheLastSampleAndTheTenthLatches) {
  Booted b;
  Rig& r = b.rig;
  r.gyro.chip.set_rate_code(1310);  // 10 °/s: 10 m° per tick
  r.tick(100);
  ASSERT_EQ(r.board->rotation_mdeg(), 1000);
  r.gyro.present = false;
  r.tick(9);  // nine failed reads, each integrating the held 10 m°
  EXPECT_EQ(r.board->rotation_mdeg(), 1090);
  EXPECT_EQ(r.board->fault_code(), 0);
  EXPECT_EQ(r.board->sensors().gyro_misses, 9U);
  r.tick(1);  // the tenth: latched, nothing integrated
  EXPECT_EQ(r.board->rotation_mdeg(), 1090);
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Lost);
  EXPECT_EQ(r.board->fault_code(), 6001);
  // Lost: the angle stays; configure() every 100 ticks (WHO_AM_I first).
  EXPECT_EQ(ticks_counting(r, 90, kImu, 0x75), 1U);  // ticks 111..200: the attempt at 200
  EXPECT_EQ(r.board->rotation_mdeg(), 1090);
  r.gyro.present = true;
  r.tick(100);  // ticks 201..300: configured again at 300 (that tick reads nothing)
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Ok);
  EXPECT_EQ(r.board->rotation_mdeg(), 1090);
  r.tick(10);
  EXPECT_EQ(r.board->rotation_mdeg(), 1190);  // continues from where it stopped
}

TEST(BoardSensors, AStuckBusLatchesBothWithItsError) {
  Booted b;
  Rig& r = b.rig;
  r.fail_bus(xy_i2c::Status::BusError);
  r.tick(250);
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Lost);
  EXPECT_EQ(r.board->fault_code(), 6003);
  r.tick(500);
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Lost);
  EXPECT_EQ(r.board->fault_code(), 5003);
  r.heal_bus();
  r.tick(1000);
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Ok);
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Ok);
}

TEST(BoardSensors, AForeignGyroIsLatched) {
  Rig r;
  r.gyro.chip.set_who_am_i(0x12);
  r.boot();
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Foreign);
  EXPECT_EQ(r.board->fault_code(), 6004);
  EXPECT_FALSE(r.gyro.chip.awake());  // nothing written: it still sleeps
  r.i2c.clear_log();
  EXPECT_EQ(ticks_counting_to(r, 1000, kImu), 0U);
}

TEST(BoardSensors, ABoardWithoutASensorBusDrivesNothingAndRaisesNoFault) {
  Rig r;
  r.board = std::make_unique<Board>([&] {
    Hardware hw = r.hardware();
    hw.i2c = {};
    return hw;
  }());
  (void)r.board->boot();
  r.tick(1000);
  EXPECT_EQ(r.board->sensors().temperature, SensorState::Unwired);
  EXPECT_EQ(r.board->sensors().gyro, SensorState::Unwired);
  EXPECT_EQ(r.board->fault_code(), 0);
  const Subs s = ask(r);
  EXPECT_EQ(s.temperature, -99999);
  EXPECT_EQ(s.rotation, 0);
}

// Sensors never block motion (docs/sensors.md): a move with both sensors failing throughout
// gives the same motor outputs, tick for tick, as one with healthy sensors.
TEST(BoardSensors, FailingSensorsNeverChangeMotion) {
  Rig good, bad;
  for (Rig* r : {&good, &bad}) {
    r->in.encoder[0] = {5, 0, 1};  // 10 mm, homed
    r->in.encoder[1] = {5, 0, 1};
  }
  bad.tmp117.present = false;
  good.boot();
  bad.boot();
  good.gyro.chip.set_rate_code(5000);
  for (Rig* r : {&good, &bad}) r->send(C::Goto, 30000, C::Move, 5000);
  for (int t = 0; t < 5000; ++t) {
    if (t == 700) bad.fail_bus(xy_i2c::Status::DataNack);
    if (t == 2600) bad.heal_bus();
    good.tick();
    bad.tick();
    for (std::size_t a = 0; a < kAxes; ++a) {
      ASSERT_EQ(good.motor[a].steps, bad.motor[a].steps) << "tick " << t;
      ASSERT_EQ(good.motor[a].dir, bad.motor[a].dir) << "tick " << t;
      ASSERT_EQ(good.motor[a].enable, bad.motor[a].enable) << "tick " << t;
    }
  }
  EXPECT_NE(bad.board->fault_code(), 0);
  EXPECT_EQ(good.board->position_um(Axis::X), 30000);
  EXPECT_EQ(bad.board->position_um(Axis::X), 30000);
}

// The echo reference model predicts the sensors from the device models alone: a board that
// reported the angle one sample late, or a stale temperature, would disagree with it.
TEST(BoardSensors, TheEchoModelAgreesFromTheDeviceModels) {
  Rig r;
  r.boot();
  model::xy_echo::BoardChecker checker(*r.board, ap::sim::xy::boot_facts_of(r));
  std::vector<std::string> bad;
  xy_frame::SubscriberSlots s{};
  s[0] = {Sub::TemperatureMc, 0};
  s[1] = {Sub::RotationMdeg, 0};
  const std::array<std::int16_t, 4> rates{11790, -3, 32767, -32768};
  for (int t = 0; t < 4000; ++t) {
    if (t % 1000 == 0) r.gyro.chip.set_rate_code(rates[static_cast<std::size_t>(t / 1000)]);
    if (t % 700 == 0) r.tmp117.chip.set_temperature_mc(-130000 + t * 97);
    if (t == 1500) r.tmp117.present = false;
    if (t == 2300) r.tmp117.present = true;
    if (t == 3100) r.gyro.present = false;
    if (t == 3350) r.gyro.present = true;
    if (t % 10 == 0) {
      const auto f = Rig::bytes_of(Rig::frame_of(++r.seq, C::Nop, 0, C::Nop, 0, s));
      r.send_raw(f);
      checker.rx(f);
    }
    const std::size_t before = r.tx.size();
    r.tick();
    const std::span<const model::xy_echo::EchoBytes> sent(r.tx.data() + before, r.tx.size() - before);
    for (auto& m : checker.after_tick(sent, ap::sim::xy::sensors_of(r))) {
      if (bad.size() < 5) bad.push_back(m);
    }
  }
  EXPECT_TRUE(bad.empty()) << bad.front();
  EXPECT_EQ(checker.model().rotation_mdeg(), r.board->rotation_mdeg());
}
