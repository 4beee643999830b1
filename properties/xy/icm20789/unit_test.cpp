// ICM-20789: driver, device model and the rotation integrator (docs/sensors.md).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "core/xy/icm20789/driver.hpp"
#include "core/xy/icm20789/rotation.hpp"
#include "models/xy/i2c/bus.hpp"
#include "models/xy/icm20789/device.hpp"
#include "reference.hpp"

namespace {

namespace chip = ap::xy_icm20789;
namespace bus = ap::xy_i2c;
using ap::model::xy_i2c::Bus;
using ap::model::xy_icm20789::Device;
using chip::Error;
using chip::FullScale;
using chip::Rotation;
namespace reg = chip::reg;
using icm_test::reference_mdeg;

constexpr FullScale kScales[] = {FullScale::Dps250, FullScale::Dps500, FullScale::Dps1000, FullScale::Dps2000};

struct Bench {
  Device device;
  Bus bus;
  chip::Driver driver{bus.port()};
  Bench() { bus.attach(device); }
};

std::vector<std::uint8_t> registers(const Device& d) {
  std::vector<std::uint8_t> out;
  for (unsigned r = 0; r < 128; ++r) out.push_back(d.reg(static_cast<std::uint8_t>(r)));
  return out;
}

// ---- driver ---------------------------------------------------------------------------------

TEST(icm20789_driver, configure_wakes_and_sets_every_documented_field) {
  for (const auto fs : kScales) {
    Bench b;
    EXPECT_FALSE(b.device.awake());
    const auto r = b.driver.configure(fs);
    ASSERT_TRUE(r);
    EXPECT_EQ(*r, fs);
    EXPECT_TRUE(b.device.awake());
    EXPECT_EQ(b.device.reg(reg::kPwrMgmt1), 0x01u);
    EXPECT_EQ(b.device.reg(reg::kSmplrtDiv), 0x00u);
    EXPECT_EQ(b.device.reg(reg::kConfig), 0x82u);  // reserved bit 7 kept, DLPF_CFG = 2
    EXPECT_EQ(b.device.reg(reg::kGyroConfig), static_cast<unsigned>(fs) << 3);
    EXPECT_EQ(b.device.full_scale(), fs);
    EXPECT_EQ(b.driver.full_scale(), fs);
    // WHO_AM_I is the first transaction, before anything is written.
    ASSERT_FALSE(b.bus.log().empty());
    EXPECT_EQ(b.bus.log()[0].tx, (std::vector<std::uint8_t>{0x75}));
  }
}

TEST(icm20789_driver, wrong_who_am_i_is_typed_and_writes_nothing) {
  // 0x98 ICM-20689, 0x12 ICM-20602, 0x70 MPU-6500, bus floating high / low.
  for (std::uint8_t who : std::vector<std::uint8_t>{0x98, 0x12, 0x70, 0xFF, 0x00, 0x02}) {
    Bench b;
    b.device.set_who_am_i(who);
    const auto before = registers(b.device);
    const auto r = b.driver.configure();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error(), Error::WrongDevice) << int{who};
    EXPECT_EQ(b.bus.writes(), 0u);
    EXPECT_EQ(registers(b.device), before);
    EXPECT_FALSE(b.device.awake());
    EXPECT_FALSE(b.driver.configured());
    EXPECT_EQ(b.driver.read_rate_z().error(), Error::NotConfigured);
  }
}

TEST(icm20789_driver, nack_on_a_wrong_address_and_no_port) {
  Bench b;
  chip::Driver other{b.bus.port(), chip::kAddressAd0High};
  const auto before = registers(b.device);
  EXPECT_EQ(other.configure().error(), Error::AddressNack);
  EXPECT_EQ(registers(b.device), before);
  chip::Driver none{bus::Port{}};
  EXPECT_EQ(none.configure().error(), Error::NoPort);
  EXPECT_EQ(none.read_rate_z().error(), Error::NotConfigured);
}

TEST(icm20789_driver, configure_under_every_bus_failure) {
  Bench probe;
  ASSERT_TRUE(probe.driver.configure());
  const auto transactions = static_cast<unsigned>(probe.bus.log().size());
  ASSERT_EQ(transactions, 13u);  // WHO_AM_I, then read / write / read back of four registers
  for (unsigned at = 0; at < transactions; ++at) {
    for (auto [status, error] : {std::pair{bus::Status::AddressNack, Error::AddressNack},
                                 std::pair{bus::Status::DataNack, Error::DataNack},
                                 std::pair{bus::Status::BusError, Error::BusError}}) {
      Bench b;
      const auto before = registers(b.device);
      b.bus.fail_at(at, status);
      const auto r = b.driver.configure(FullScale::Dps500);
      ASSERT_FALSE(r) << at;
      EXPECT_EQ(r.error(), error);
      EXPECT_FALSE(b.driver.configured());
      if (at < 3) {
        EXPECT_EQ(registers(b.device), before) << at;
      }
      ASSERT_TRUE(b.driver.configure(FullScale::Dps500));
      EXPECT_EQ(b.device.full_scale(), FullScale::Dps500);
    }
  }
}

struct StubbornDevice : Device {
  bus::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) override {
    if (tx.size() == 2 && tx[0] == reg::kGyroConfig) return Device::transfer(address, tx.first(1), rx);
    return Device::transfer(address, tx, rx);
  }
};

TEST(icm20789_driver, a_field_that_does_not_stick_is_a_mismatch) {
  StubbornDevice d;
  Bus bus;
  bus.attach(d);
  chip::Driver driver{bus.port()};
  // FS_SEL 0 would equal the reset value and read back right by accident.
  EXPECT_EQ(driver.configure(FullScale::Dps1000).error(), Error::ConfigMismatch);
  EXPECT_FALSE(driver.configured());
}

TEST(icm20789_driver, every_rate_code_reads_back_exactly) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  for (std::int32_t code = -32768; code <= 32767; ++code) {
    b.device.set_rate_code(static_cast<std::int16_t>(code));
    const auto r = b.driver.read_rate_z();
    ASSERT_TRUE(r);
    ASSERT_EQ(*r, code);
    if ((code & 0xFFF) == 0) b.bus.clear_log();
  }
}

TEST(icm20789_driver, read_failure_is_typed_and_changes_nothing) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  b.device.set_rate_code(-1234);
  for (auto [status, error] : {std::pair{bus::Status::AddressNack, Error::AddressNack},
                               std::pair{bus::Status::DataNack, Error::DataNack},
                               std::pair{bus::Status::BusError, Error::BusError}}) {
    b.bus.fail_at(0, status);
    const auto r = b.driver.read_rate_z();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error(), error);
    EXPECT_TRUE(b.driver.configured());
    EXPECT_EQ(*b.driver.read_rate_z(), -1234);
  }
}

// The whole chain, bus included: 90 °/s for 4 s is one turn and lands exactly on 0.
TEST(icm20789_driver, one_turn_through_the_bus) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  b.device.set_rate_mdps(90000);
  Rotation rot;
  for (int t = 0; t < 4000; ++t) {
    const auto r = b.driver.read_rate_z();
    ASSERT_TRUE(r);
    ASSERT_EQ(*r, 11790);
    rot.step(*r);
    if (t == 999) {
      EXPECT_EQ(rot.mdeg(), 90000);
    }
    if ((t & 0x3FF) == 0) b.bus.clear_log();
  }
  EXPECT_EQ(rot.mdeg(), 0);
  EXPECT_EQ(rot.units(), 0);
}

// ---- model ----------------------------------------------------------------------------------

TEST(icm20789_model, power_up_values_and_read_only_registers) {
  Device d;
  EXPECT_EQ(d.reg(reg::kPwrMgmt1), 0x41u);
  EXPECT_EQ(d.reg(reg::kWhoAmI), 0x03u);
  EXPECT_EQ(d.reg(reg::kConfig), 0x80u);
  EXPECT_EQ(d.reg(reg::kGyroConfig), 0x00u);
  EXPECT_FALSE(d.awake());
  Bus bus;
  bus.attach(d);
  const std::vector<std::uint8_t> w{0x47, 0x12, 0x34}, who{0x75, 0x55}, bad{0x80};
  EXPECT_EQ(bus.transfer(0x68, w, {}), bus::Status::Ok);
  EXPECT_EQ(bus.transfer(0x68, who, {}), bus::Status::Ok);
  EXPECT_EQ(d.reg(reg::kGyroZoutH), 0u);
  EXPECT_EQ(d.reg(reg::kWhoAmI), 0x03u);
  EXPECT_EQ(bus.transfer(0x68, bad, {}), bus::Status::DataNack);
  EXPECT_EQ(bus.transfer(0x63, w, {}), bus::Status::AddressNack);
}

TEST(icm20789_model, asleep_the_output_holds_and_device_reset_restores) {
  Bench b;
  b.device.set_rate_mdps(10000);
  std::array<std::uint8_t, 2> z{};
  const std::array<std::uint8_t, 1> ptr{reg::kGyroZoutH};
  ASSERT_EQ(b.bus.transfer(0x68, ptr, z), bus::Status::Ok);
  EXPECT_EQ(z[0], 0u);  // asleep since power-up
  ASSERT_TRUE(b.driver.configure());
  EXPECT_EQ(*b.driver.read_rate_z(), 1310);
  const std::array<std::uint8_t, 2> reset{reg::kPwrMgmt1, 0x80};
  ASSERT_EQ(b.bus.transfer(0x68, reset, {}), bus::Status::Ok);
  EXPECT_EQ(b.device.reg(reg::kPwrMgmt1), 0x41u);
  EXPECT_EQ(b.device.reg(reg::kConfig), 0x80u);
  EXPECT_FALSE(b.device.awake());
}

TEST(icm20789_model, rate_to_code_per_full_scale_saturates) {
  EXPECT_EQ(Device::code_for_mdps(100000, FullScale::Dps250), 13100);
  EXPECT_EQ(Device::code_for_mdps(100000, FullScale::Dps500), 6550);
  EXPECT_EQ(Device::code_for_mdps(100000, FullScale::Dps1000), 3280);
  EXPECT_EQ(Device::code_for_mdps(100000, FullScale::Dps2000), 1640);
  EXPECT_EQ(Device::code_for_mdps(-100000, FullScale::Dps250), -13100);
  EXPECT_EQ(Device::code_for_mdps(400000, FullScale::Dps250), 32767);
  EXPECT_EQ(Device::code_for_mdps(-400000, FullScale::Dps250), -32768);
}

// ---- rotation -------------------------------------------------------------------------------

static_assert(Rotation{}.mdeg() == 0);
static_assert(Rotation{FullScale::Dps1000}.turn_units() == 360000 * 164);

TEST(icm20789_rotation, wraps_exactly_at_360000) {
  Rotation rot;  // ±250 °/s: raw 131 is 1 °/s, 1 m° per tick
  for (int t = 0; t < 359999; ++t) rot.step(131);
  EXPECT_EQ(rot.mdeg(), 359999);
  rot.step(131);
  EXPECT_EQ(rot.mdeg(), 0);
  EXPECT_EQ(rot.units(), 0);
  rot.step(131);
  EXPECT_EQ(rot.mdeg(), 1);
}

TEST(icm20789_rotation, wraps_below_zero) {
  Rotation rot;
  rot.step(-1);  // -1/131 m°
  EXPECT_EQ(rot.mdeg(), 359999);
  EXPECT_EQ(rot.units(), rot.turn_units() - 1);
  rot.step(1);
  EXPECT_EQ(rot.mdeg(), 0);
  for (int t = 0; t < 360000; ++t) rot.step(-131);
  EXPECT_EQ(rot.units(), 0);
}

TEST(icm20789_rotation, constant_rate_full_turns_land_exactly) {
  // 250 °/s for 1.44 s, 100 °/s for 3.6 s, 1 °/s for 360 s, 1000 °/s for 0.36 s: whole turns.
  struct Case {
    FullScale fs;
    std::int16_t raw;
    int ticks;
  };
  for (const auto& c : {Case{FullScale::Dps250, 32750, 1440}, Case{FullScale::Dps250, -13100, 3600},
                        Case{FullScale::Dps250, 131, 360000}, Case{FullScale::Dps500, 6550, 3600},
                        Case{FullScale::Dps1000, 3280, 3600}, Case{FullScale::Dps2000, -1640, 3600},
                        Case{FullScale::Dps2000, 16400, 360}}) {
    Rotation rot{c.fs};
    for (int t = 0; t < 7; ++t) rot.step(static_cast<std::int16_t>(t * 1000 - 3000));  // arbitrary start
    const auto start = rot.units();
    for (int t = 0; t < c.ticks; ++t) {
      rot.step(c.raw);
      ASSERT_GE(rot.mdeg(), 0);
      ASSERT_LT(rot.mdeg(), 360000);
    }
    EXPECT_EQ(rot.units(), start) << int{c.raw};
  }
}

TEST(icm20789_rotation, saturation_codes) {
  for (int fs = 0; fs < 4; ++fs) {
    Rotation up{static_cast<FullScale>(fs)}, down{static_cast<FullScale>(fs)};
    std::int64_t sum_up = 0, sum_down = 0;
    for (int t = 0; t < 100000; ++t) {
      up.step(32767);
      down.step(-32768);
      sum_up += 32767;
      sum_down -= 32768;
      if (t % 997 == 0 || t == 99999) {
        ASSERT_EQ(up.mdeg(), reference_mdeg(sum_up, fs)) << fs << " " << t;
        ASSERT_EQ(down.mdeg(), reference_mdeg(sum_down, fs)) << fs << " " << t;
      }
    }
  }
  // 250.12 °/s for 1 s: 250129.77 m°; -250.14 °/s for 1 s: -250137.4 m° = 109862.6 m°.
  Rotation a, b;
  for (int t = 0; t < 1000; ++t) {
    a.step(32767);
    b.step(-32768);
  }
  EXPECT_EQ(a.mdeg(), 250129);
  EXPECT_EQ(b.mdeg(), 109862);
}

TEST(icm20789_rotation, zero_references_the_present_orientation) {
  Rotation rot;
  for (int t = 0; t < 500; ++t) rot.step(1000);
  rot.zero();
  EXPECT_EQ(rot.mdeg(), 0);
  rot.step(131);
  EXPECT_EQ(rot.mdeg(), 1);
}

}  // namespace
