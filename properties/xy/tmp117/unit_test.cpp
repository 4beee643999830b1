// TMP117: conversion, driver and device model (docs/sensors.md).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "core/xy/tmp117/convert.hpp"
#include "core/xy/tmp117/driver.hpp"
#include "models/xy/i2c/bus.hpp"
#include "models/xy/tmp117/device.hpp"
#include "reference.hpp"

namespace {

namespace chip = ap::xy_tmp117;
namespace bus = ap::xy_i2c;
using ap::model::xy_i2c::Bus;
using ap::model::xy_tmp117::Device;
using chip::Error;
using chip::Reg;
using tmp117_test::reference_mc;

static_assert(chip::millicelsius(0x0C80) == 25000);

// ---- conversion ---------------------------------------------------------------------------

TEST(tmp117_convert, every_code_matches_the_exact_fraction) {
  unsigned mismatches = 0;
  for (std::uint32_t code = 0; code <= 0xFFFFu; ++code) {
    const auto got = chip::millicelsius(static_cast<std::uint16_t>(code));
    if (got != reference_mc(code)) {
      if (++mismatches <= 10) ADD_FAILURE() << "code 0x" << std::hex << code << std::dec << ": " << got
                                            << " m°C, exact rounding gives " << reference_mc(code);
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

// The datasheet's temperature data format table (SNOSD82D, 7.3.3), row by row, in m°C,
// rounded where the table has fractions of a m°C.
TEST(tmp117_convert, datasheet_table) {
  struct Row {
    std::uint16_t code;
    std::int32_t mc;
  };
  const std::vector<Row> rows{
      {0x8000, -256000}, {0xF380, -25000}, {0xFF80, -1000}, {0xFFF0, -125}, {0xFFFF, -8},
      {0x0000, 0},       {0x0001, 8},      {0x0010, 125},   {0x0080, 1000}, {0x0C80, 25000},
      {0x3200, 100000},  {0x7FFF, 255992},
  };
  for (const auto& r : rows) EXPECT_EQ(chip::millicelsius(r.code), r.mc) << std::hex << r.code;
}

TEST(tmp117_convert, documented_range) {
  EXPECT_EQ(chip::kMinMilliCelsius, -256000);
  EXPECT_EQ(chip::kMaxMilliCelsius, 255992);
}

TEST(tmp117_convert, halves_round_away_from_zero) {
  EXPECT_EQ(chip::millicelsius(0x0008), 63);    //  62.5
  EXPECT_EQ(chip::millicelsius(0xFFF8), -63);   // -62.5
  EXPECT_EQ(chip::millicelsius(0x0018), 188);   //  187.5
  EXPECT_EQ(chip::millicelsius(0xFFE8), -188);  // -187.5
  EXPECT_EQ(chip::millicelsius(0x0009), 70);    //  70.3125
  EXPECT_EQ(chip::millicelsius(0xFFF7), -70);
}

TEST(tmp117_convert, odd_symmetric_and_monotonic) {
  std::int32_t prev = chip::millicelsius(0x8000);
  for (std::int32_t s = -32767; s <= 32767; ++s) {
    const auto c = static_cast<std::uint16_t>(s);
    const auto neg = static_cast<std::uint16_t>(-s);
    ASSERT_EQ(chip::millicelsius(c), -chip::millicelsius(neg)) << s;
    ASSERT_GE(chip::millicelsius(c), prev) << s;
    ASSERT_LE(chip::millicelsius(c) - prev, 8) << s;
    prev = chip::millicelsius(c);
  }
}

// ---- driver against the model -------------------------------------------------------------

struct Bench {
  Device device;
  Bus bus;
  chip::Driver driver{bus.port()};
  Bench() { bus.attach(device); }
};

std::vector<std::uint16_t> registers(const Device& d) {
  std::vector<std::uint16_t> out;
  for (auto r : {Reg::TempResult, Reg::Configuration, Reg::THighLimit, Reg::TLowLimit, Reg::EepromUl,
                 Reg::Eeprom1, Reg::Eeprom2, Reg::TempOffset, Reg::Eeprom3, Reg::DeviceId}) {
    out.push_back(d.reg(r));
  }
  return out;
}

TEST(tmp117_driver, configure_checks_the_id_then_writes_the_documented_configuration) {
  Bench b;
  const auto r = b.driver.configure();
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, 0u);
  EXPECT_TRUE(b.driver.configured());
  EXPECT_EQ(b.device.reg(Reg::Configuration) & chip::cfg::kWritable, 0x0120u);
  EXPECT_EQ(chip::kConfigWord, 0x0120u);
  ASSERT_EQ(b.bus.log().size(), 3u);
  EXPECT_EQ(b.bus.log()[0].tx, (std::vector<std::uint8_t>{0x0F}));
  EXPECT_EQ(b.bus.log()[1].tx, (std::vector<std::uint8_t>{0x01, 0x01, 0x20}));
  EXPECT_EQ(b.bus.writes(), 1u);
}

TEST(tmp117_driver, result_every_250_ms_after_a_125_ms_conversion) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  const unsigned before = b.device.conversions();
  EXPECT_EQ(Device::cycle_us(2, 1), chip::kConversionPeriodMs * 1000u);
  b.device.advance_ms(124);
  EXPECT_EQ(b.device.conversions(), before);
  b.device.advance_ms(1);
  EXPECT_EQ(b.device.conversions(), before + 1);
  b.device.advance_ms(1000);
  EXPECT_EQ(b.device.conversions(), before + 5);
}

TEST(tmp117_driver, no_temperature_before_the_first_conversion) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  const auto r = b.driver.read_mc();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), Error::NoConversionYet);
  b.device.set_temperature_mc(23456);
  b.device.advance_ms(125);
  const auto t = b.driver.read_mc();
  ASSERT_TRUE(t);
  EXPECT_EQ(*t, reference_mc(b.device.reg(Reg::TempResult)));
  EXPECT_LE(std::abs(*t - 23456), 4);
}

TEST(tmp117_driver, every_code_through_the_bus) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  for (std::uint32_t code = 0; code <= 0xFFFFu; ++code) {
    b.device.set_result_code(static_cast<std::uint16_t>(code));
    const auto r = b.driver.read_mc();
    if (code == 0x8000u) {
      ASSERT_FALSE(r);
      ASSERT_EQ(r.error(), Error::NoConversionYet);
    } else {
      ASSERT_TRUE(r) << code;
      ASSERT_EQ(*r, reference_mc(code)) << std::hex << code;
    }
    if ((code & 0xFFFu) == 0) b.bus.clear_log();
  }
}

TEST(tmp117_driver, revision_nibble_is_accepted_and_reported) {
  Bench b;
  b.device.set_device_id(0x3117);
  const auto r = b.driver.configure();
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, 3u);
  EXPECT_EQ(b.driver.revision(), 3u);
}

TEST(tmp117_driver, wrong_device_id_is_typed_and_writes_nothing) {
  for (std::uint16_t id : std::vector<std::uint16_t>{0x0116, 0x1116, 0x0119, 0x0000, 0xFFFF, 0x0017}) {
    Bench b;
    b.device.set_device_id(id);
    const auto before = registers(b.device);
    const auto r = b.driver.configure();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error(), Error::WrongDeviceId) << id;
    EXPECT_EQ(b.bus.writes(), 0u);
    EXPECT_EQ(registers(b.device), before);
    EXPECT_FALSE(b.driver.configured());
    EXPECT_EQ(b.driver.read_mc().error(), Error::NotConfigured);
  }
}

TEST(tmp117_driver, nack_on_a_wrong_address) {
  Bench b;
  chip::Driver other{b.bus.port(), chip::kAddressVplus};
  const auto before = registers(b.device);
  const auto r = other.configure();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), Error::AddressNack);
  EXPECT_EQ(registers(b.device), before);
  EXPECT_FALSE(other.configured());
}

TEST(tmp117_driver, no_port_and_not_configured_send_nothing) {
  chip::Driver none{ap::xy_i2c::Port{}};
  EXPECT_EQ(none.configure().error(), Error::NoPort);
  Bench b;
  EXPECT_EQ(b.driver.read_mc().error(), Error::NotConfigured);
  EXPECT_TRUE(b.bus.log().empty());
}

// Every transaction of configure() failing in every way: a typed error, the driver unchanged,
// nothing written when the write itself failed, and a retry on a healthy bus works.
TEST(tmp117_driver, configure_under_every_bus_failure) {
  const std::vector<std::pair<bus::Status, Error>> faults{{bus::Status::AddressNack, Error::AddressNack},
                                                          {bus::Status::DataNack, Error::DataNack},
                                                          {bus::Status::BusError, Error::BusError}};
  for (unsigned at = 0; at < 3; ++at) {
    for (const auto& [status, error] : faults) {
      Bench b;
      const auto before = registers(b.device);
      b.bus.fail_at(at, status);
      const auto r = b.driver.configure();
      ASSERT_FALSE(r) << at;
      EXPECT_EQ(r.error(), error);
      EXPECT_FALSE(b.driver.configured());
      if (at <= 1) {
        EXPECT_EQ(registers(b.device), before) << at;
      }
      ASSERT_TRUE(b.driver.configure());
      EXPECT_EQ(b.device.reg(Reg::Configuration) & chip::cfg::kWritable, chip::kConfigWord);
    }
  }
}

TEST(tmp117_driver, read_failure_is_typed_and_changes_nothing) {
  Bench b;
  ASSERT_TRUE(b.driver.configure());
  b.device.set_temperature_mc(-12345);
  b.device.advance_ms(125);
  const auto first = b.driver.read_mc();
  ASSERT_TRUE(first);
  for (auto [status, error] : {std::pair{bus::Status::AddressNack, Error::AddressNack},
                               std::pair{bus::Status::DataNack, Error::DataNack},
                               std::pair{bus::Status::BusError, Error::BusError}}) {
    b.bus.fail_at(0, status);
    const auto r = b.driver.read_mc();
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error(), error);
    EXPECT_TRUE(b.driver.configured());
    EXPECT_EQ(*b.driver.read_mc(), *first);
  }
}

// A part that takes no writes to Configuration (a TMP117 held in reset, a look-alike).
struct StubbornDevice : Device {
  bus::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) override {
    if (tx.size() == 3 && tx[0] == chip::reg_address(Reg::Configuration)) return Device::transfer(address, tx.first(1), rx);
    return Device::transfer(address, tx, rx);
  }
};

TEST(tmp117_driver, configuration_that_does_not_stick_is_a_mismatch) {
  StubbornDevice d;
  Bus bus;
  bus.attach(d);
  chip::Driver driver{bus.port()};
  const auto r = driver.configure();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), Error::ConfigMismatch);
  EXPECT_FALSE(driver.configured());
}

// ---- the model ------------------------------------------------------------------------------

TEST(tmp117_model, power_up_values) {
  Device d;
  EXPECT_EQ(d.reg(Reg::TempResult), 0x8000u);
  EXPECT_EQ(d.reg(Reg::Configuration), 0x0220u);
  EXPECT_EQ(d.reg(Reg::THighLimit), 0x6000u);
  EXPECT_EQ(d.reg(Reg::TLowLimit), 0x8000u);
  EXPECT_EQ(d.reg(Reg::EepromUl), 0x0000u);
  EXPECT_EQ(d.reg(Reg::TempOffset), 0x0000u);
  EXPECT_EQ(d.reg(Reg::DeviceId), 0x0117u);
  // Reset configuration: CONV = 100, AVG = 01: first result after 125 ms, then every 1 s.
  d.advance_ms(125);
  EXPECT_EQ(d.conversions(), 1u);
  d.advance_ms(1000);
  EXPECT_EQ(d.conversions(), 2u);
}

TEST(tmp117_model, read_only_registers_ignore_writes_and_bad_pointers_are_refused) {
  Device d;
  Bus bus;
  bus.attach(d);
  const std::vector<std::uint8_t> w0{0x00, 0x12, 0x34}, wf{0x0F, 0x00, 0x00}, bad{0x09};
  EXPECT_EQ(bus.transfer(0x48, w0, {}), bus::Status::Ok);
  EXPECT_EQ(bus.transfer(0x48, wf, {}), bus::Status::Ok);
  EXPECT_EQ(d.reg(Reg::TempResult), 0x8000u);
  EXPECT_EQ(d.reg(Reg::DeviceId), 0x0117u);
  EXPECT_EQ(bus.transfer(0x48, bad, {}), bus::Status::DataNack);
  EXPECT_EQ(bus.transfer(0x47, bad, {}), bus::Status::AddressNack);
}

TEST(tmp117_model, data_ready_mod10_soft_reset_one_shot_offset) {
  Device d;
  Bus bus;
  bus.attach(d);
  chip::Driver drv{bus.port()};
  ASSERT_TRUE(drv.configure());
  d.advance_ms(125);
  EXPECT_NE(d.reg(Reg::Configuration) & chip::cfg::kDataReady, 0u);
  ASSERT_TRUE(drv.read_mc());
  EXPECT_EQ(d.reg(Reg::Configuration) & chip::cfg::kDataReady, 0u);

  const std::vector<std::uint8_t> mod10{0x01, 0x09, 0x20};  // MOD = 10
  ASSERT_EQ(bus.transfer(0x48, mod10, {}), bus::Status::Ok);
  EXPECT_EQ(chip::cfg::mod(d.reg(Reg::Configuration)), 0u);

  d.set_temperature_mc(25000);
  const std::vector<std::uint8_t> offset{0x07, 0xFF, 0x80};  // -1 °C
  ASSERT_EQ(bus.transfer(0x48, offset, {}), bus::Status::Ok);
  const std::vector<std::uint8_t> one_shot{0x01, 0x0C, 0x00};  // MOD = 11, AVG = 0
  ASSERT_EQ(bus.transfer(0x48, one_shot, {}), bus::Status::Ok);
  const unsigned n = d.conversions();
  d.advance_ms(100);
  EXPECT_EQ(d.conversions(), n + 1);
  EXPECT_EQ(chip::cfg::mod(d.reg(Reg::Configuration)), chip::cfg::kModShutdown);
  EXPECT_EQ(*drv.read_mc(), 24000);
  d.advance_ms(5000);
  EXPECT_EQ(d.conversions(), n + 1);

  const std::vector<std::uint8_t> soft_reset{0x01, 0x00, 0x02};
  ASSERT_EQ(bus.transfer(0x48, soft_reset, {}), bus::Status::Ok);
  EXPECT_EQ(d.reg(Reg::Configuration), 0x0220u);
  EXPECT_EQ(d.reg(Reg::TempOffset), 0x0000u);
  EXPECT_EQ(drv.read_mc().error(), Error::NoConversionYet);
}

}  // namespace
