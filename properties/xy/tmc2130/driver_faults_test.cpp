// TMC2130 driver under SPI bus failures: a single failed transfer at any point of any
// operation (plain access, read-modify-write, the re-initialisation after a chip reset) is
// reported as Error::BusFailure, never as success; a shadow only changes once its write went
// out; and the next operation on a healthy bus recovers (chip registers == shadows).
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/xy/tmc2130/current.hpp"
#include "core/xy/tmc2130/driver.hpp"
#include "models/xy/tmc2130/device.hpp"

namespace {

namespace chip = ap::xy_tmc2130;
using ap::model::xy_tmc2130::Device;
using chip::Field;
using chip::Reg;

// A bus that fails exactly one transfer: the `fail_at`-th (0-based) after arming. The failed
// datagram never reaches the chip.
struct FlakyBench {
  Device device;
  unsigned transfers = 0;
  std::optional<unsigned> fail_at;
  chip::Driver driver{chip::SpiPort{&FlakyBench::spi, this}};

  static bool spi(void* context, const chip::Datagram& tx, chip::Datagram& rx) {
    auto* self = static_cast<FlakyBench*>(context);
    const unsigned n = self->transfers++;
    if (self->fail_at && n == *self->fail_at) return false;
    rx = self->device.transfer(tx);
    return true;
  }
  void arm(std::optional<unsigned> k) {
    transfers = 0;
    fail_at = k;
  }
  bool chip_matches_shadows() const {
    for (const auto& r : chip::kRegisters) {
      if (!chip::writable(r.access)) continue;
      const std::uint32_t m = chip::implemented_mask(r.reg);
      if ((device.chip_register(r.reg) & m) != (driver.shadow(r.reg) & m)) return false;
    }
    return true;
  }
};

struct Case {
  std::string name;
  std::function<void(FlakyBench&)> prepare;                 // healthy bus
  std::function<std::optional<chip::Error>(FlakyBench&)> op;   // nullopt on success
};

template <class T>
std::optional<chip::Error> error_of(const chip::Result<T>& r) {
  if (r) return std::nullopt;
  return r.error();
}

void initialised(FlakyBench& b) {
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_TOFF>(5));
  ASSERT_TRUE(b.driver.set<Field::IHOLD_IRUN_IRUN>(12));
}

void initialised_then_reset(FlakyBench& b) {
  initialised(b);
  b.device.power_cycle();
}

std::vector<Case> cases() {
  return {
      {"init on a fresh chip", [](FlakyBench&) {}, [](FlakyBench& b) { return error_of(b.driver.init()); }},
      {"check_reset, no reset", initialised, [](FlakyBench& b) { return error_of(b.driver.check_reset()); }},
      {"check_reset after a reset", initialised_then_reset,
       [](FlakyBench& b) { return error_of(b.driver.check_reset()); }},
      {"read of a readable register", initialised, [](FlakyBench& b) { return error_of(b.driver.read(Reg::CHOPCONF)); }},
      {"read after a reset", initialised_then_reset,
       [](FlakyBench& b) { return error_of(b.driver.read(Reg::CHOPCONF)); }},
      {"get after a reset", initialised_then_reset,
       [](FlakyBench& b) { return error_of(b.driver.get<Field::CHOPCONF_TOFF>()); }},
      {"whole-register write, readable", initialised,
       [](FlakyBench& b) { return error_of(b.driver.write(Reg::CHOPCONF, 0x00010004u)); }},
      {"whole-register write, write-only", initialised,
       [](FlakyBench& b) { return error_of(b.driver.write(Reg::TPOWERDOWN, 33)); }},
      {"field set, readable (RMW)", initialised,
       [](FlakyBench& b) { return error_of(b.driver.set<Field::CHOPCONF_MRES>(3)); }},
      {"field set, readable, after a reset", initialised_then_reset,
       [](FlakyBench& b) { return error_of(b.driver.set<Field::CHOPCONF_MRES>(3)); }},
      {"field set, write-only, after a reset", initialised_then_reset,
       [](FlakyBench& b) { return error_of(b.driver.set<Field::IHOLD_IRUN_IHOLD>(4)); }},
  };
}

}  // namespace

TEST(tmc2130_driver_faults, every_single_bus_failure_is_reported_and_recovered) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    // How many transfers the operation takes on a healthy bus.
    FlakyBench healthy;
    c.prepare(healthy);
    healthy.arm(std::nullopt);
    ASSERT_EQ(c.op(healthy), std::nullopt);
    const unsigned n = healthy.transfers;
    ASSERT_GT(n, 0u);
    ASSERT_TRUE(healthy.chip_matches_shadows());

    for (unsigned k = 0; k < n; ++k) {
      SCOPED_TRACE("failing transfer " + std::to_string(k) + " of " + std::to_string(n));
      FlakyBench b;
      c.prepare(b);
      b.arm(k);
      EXPECT_EQ(c.op(b), chip::Error::BusFailure);
      EXPECT_EQ(b.transfers, k + 1) << "no traffic after the failed transfer";
      // The shadows never run ahead of what the chip was sent: a register nobody wrote since
      // the failure still matches, and the next operation on a healthy bus converges.
      b.arm(std::nullopt);
      EXPECT_EQ(c.op(b), std::nullopt);
      EXPECT_TRUE(b.chip_matches_shadows());
    }
  }
}

TEST(tmc2130_driver_faults, failed_write_leaves_the_shadow_alone) {
  FlakyBench b;
  initialised(b);
  const std::uint32_t before = b.driver.shadow(Reg::TPOWERDOWN);
  b.arm(0);
  const auto r = b.driver.write(Reg::TPOWERDOWN, before + 1);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), chip::Error::BusFailure);
  EXPECT_EQ(b.driver.shadow(Reg::TPOWERDOWN), before);
  EXPECT_EQ(b.device.chip_register(Reg::TPOWERDOWN), before);
}

TEST(tmc2130_driver_faults, whole_register_write_verifies_and_refuses_read_only) {
  FlakyBench b;
  initialised(b);
  b.device.clear_log();
  const auto w = b.driver.write(Reg::CHOPCONF, 0x00010004u);
  ASSERT_TRUE(w);
  EXPECT_EQ(b.driver.shadow(Reg::CHOPCONF), 0x00010004u);
  EXPECT_EQ(b.device.chip_register(Reg::CHOPCONF) & chip::implemented_mask(Reg::CHOPCONF), 0x00010004u);
  EXPECT_EQ(b.device.writes_of(Reg::CHOPCONF), 1u);
  EXPECT_GE(b.device.reads_of(Reg::CHOPCONF), 1u) << "a readable register is read back";

  b.device.clear_log();
  for (const Reg ro : {Reg::DRV_STATUS, Reg::GSTAT}) {
    const auto r = b.driver.write(ro, 1);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error(), chip::Error::NotWritable);
  }
  EXPECT_TRUE(b.device.log().empty()) << "a refused write sends nothing";
}

// GSTAT is the record of a reset: reading it right after one returns the reset flag (not a
// re-read after the re-initialisation, which would have cleared it), and the driver has
// restored every register meanwhile.
TEST(tmc2130_driver_faults, gstat_read_after_reset_reports_the_reset) {
  FlakyBench b;
  initialised(b);
  const unsigned before = b.driver.resets_recovered();
  b.device.power_cycle();
  const auto g = b.driver.read(Reg::GSTAT);
  ASSERT_TRUE(g);
  EXPECT_EQ(chip::field_get(*g, Field::GSTAT_reset), 1);
  EXPECT_EQ(b.driver.resets_recovered(), before + 1);
  EXPECT_TRUE(b.chip_matches_shadows());
  const auto again = b.driver.read(Reg::GSTAT);
  ASSERT_TRUE(again);
  EXPECT_EQ(chip::field_get(*again, Field::GSTAT_reset), 0);
}

// A driver whose port has no transfer function cannot talk to the chip: typed errors, no
// shadow change, and write-only reads still answer from the shadow.
TEST(tmc2130_driver_faults, unconnected_port_is_a_bus_failure) {
  chip::Driver d{chip::SpiPort{}};
  const auto init = d.init();
  ASSERT_FALSE(init);
  EXPECT_EQ(init.error(), chip::Error::BusFailure);
  const std::uint32_t before = d.shadow(Reg::IHOLD_IRUN);
  const auto w = d.set<Field::IHOLD_IRUN_IRUN>(20);
  ASSERT_FALSE(w);
  EXPECT_EQ(w.error(), chip::Error::BusFailure);
  EXPECT_EQ(d.shadow(Reg::IHOLD_IRUN), before);
  const auto r = d.read(Reg::CHOPCONF);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), chip::Error::BusFailure);
  const auto wo = d.read(Reg::IHOLD_IRUN);
  ASSERT_TRUE(wo);
  EXPECT_EQ(*wo, before);
}

// The current equation's documented input range (R_SENSE 1..1000 mOhm, CS 0..31, target up to
// 10 A): each bound is inclusive and one past it is a typed error.
TEST(tmc2130_current_edges, sense_resistor_and_target_bounds) {
  namespace cur = chip::current;
  for (const bool vsense : {false, true}) {
    EXPECT_TRUE(cur::current_ma(31, vsense, cur::kMinRsenseMohm));
    EXPECT_TRUE(cur::current_ma(0, vsense, cur::kMaxRsenseMohm));
    EXPECT_EQ(cur::current_ma(0, vsense, cur::kMaxRsenseMohm + 1).error(), chip::Error::CurrentOutOfRange);
    EXPECT_EQ(cur::current_ma(0, vsense, cur::kMinRsenseMohm - 1).error(), chip::Error::CurrentOutOfRange);

    EXPECT_EQ(*cur::cs_for_current(cur::kMaxCurrentMa, vsense, 110), cur::kMaxCs);
    EXPECT_EQ(cur::cs_for_current(cur::kMaxCurrentMa + 1, vsense, 110).error(), chip::Error::CurrentOutOfRange);
    EXPECT_TRUE(cur::cs_for_current(cur::kMaxCurrentMa, vsense, cur::kMaxRsenseMohm));
    EXPECT_EQ(cur::cs_for_current(1000, vsense, cur::kMaxRsenseMohm + 1).error(), chip::Error::CurrentOutOfRange);
    EXPECT_EQ(cur::cs_for_current(1000, vsense, cur::kMinRsenseMohm - 1).error(), chip::Error::CurrentOutOfRange);
  }
}
