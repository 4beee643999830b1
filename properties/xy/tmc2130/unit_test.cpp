// TMC2130 unit tests: the thesis's golden datagram, datasheet spot checks of the table,
// driver behaviour at its edges, the current equation and the generated docs.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/xy/tmc2130/current.hpp"
#include "core/xy/tmc2130/driver.hpp"
#include "harness.hpp"
#include "models/xy/tmc2130/datasheet.hpp"
#include "models/xy/tmc2130/text.hpp"

namespace {

using namespace tmc_test;
using chip::Field;
using chip::Reg;

// Thesis §9.3 / Obr. 9-5: IHOLD_IRUN holds IHOLDDELAY=7, IRUN=0x17, IHOLD=3 (TMC-API's
// default 0x00071703); setting I_RUN to 12 must send exactly 90 00 07 0C 03 and no read.
TEST(tmc2130_golden, irun_12_keeps_ihold_with_exact_datagram) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.update(Reg::IHOLD_IRUN, {{Field::IHOLD_IRUN_IHOLD, 3},
                                                {Field::IHOLD_IRUN_IRUN, 0x17},
                                                {Field::IHOLD_IRUN_IHOLDDELAY, 7}}));
  ASSERT_EQ(b.device.chip_register(Reg::IHOLD_IRUN), 0x00071703u);
  b.clear();
  ASSERT_TRUE(b.driver.set<Field::IHOLD_IRUN_IRUN>(12));
  ASSERT_EQ(b.mosi.size(), 1u);
  const chip::Datagram expected{0x90, 0x00, 0x07, 0x0C, 0x03};
  EXPECT_EQ(b.mosi[0], expected);
  EXPECT_EQ(b.device.chip_register(Reg::IHOLD_IRUN), 0x00070C03u);
  EXPECT_EQ(b.driver.shadow(Reg::IHOLD_IRUN), 0x00070C03u);
  EXPECT_EQ(b.reads(), 0u);
}

// Spot values typed in from the datasheet, independent of the table they check.
TEST(tmc2130_regmap, datasheet_spot_checks) {
  EXPECT_EQ(chip::address(Reg::IHOLD_IRUN), 0x10);
  EXPECT_EQ(chip::info(Reg::IHOLD_IRUN).access, chip::Access::W);
  EXPECT_EQ(chip::info(Field::IHOLD_IRUN_IHOLD).mask, 0x0000001Fu);
  EXPECT_EQ(chip::info(Field::IHOLD_IRUN_IRUN).mask, 0x00001F00u);
  EXPECT_EQ(chip::info(Field::IHOLD_IRUN_IRUN).shift, 8);
  EXPECT_EQ(chip::info(Field::IHOLD_IRUN_IHOLDDELAY).mask, 0x000F0000u);
  EXPECT_EQ(chip::info(Field::CHOPCONF_TOFF).mask, 0x0000000Fu);
  EXPECT_EQ(chip::info(Field::CHOPCONF_MRES).mask, 0x0F000000u);
  EXPECT_EQ(chip::info(Field::CHOPCONF_MRES).max, 8);
  EXPECT_EQ(chip::info(Field::CHOPCONF_vsense).mask, 0x00020000u);
  EXPECT_EQ(chip::info(Field::COOLCONF_sgt).mask, 0x007F0000u);
  EXPECT_TRUE(chip::info(Field::COOLCONF_sgt).is_signed);
  EXPECT_EQ(chip::info(Field::COOLCONF_sgt).min, -64);
  EXPECT_EQ(chip::info(Field::DRV_STATUS_stst).mask, 0x80000000u);
  EXPECT_EQ(chip::info(Field::DRV_STATUS_CS_ACTUAL).mask, 0x001F0000u);
  EXPECT_EQ(chip::info(Field::MSLUT3_MSLUT3).mask, 0xFFFFFFFFu);
  EXPECT_EQ(chip::address(Reg::CHOPCONF), 0x6C);
  EXPECT_EQ(chip::info(Reg::CHOPCONF).access, chip::Access::RW);
  EXPECT_EQ(chip::info(Reg::GSTAT).access, chip::Access::RC);
  EXPECT_EQ(chip::info(Reg::DRV_STATUS).access, chip::Access::R);
  EXPECT_EQ(chip::address(Reg::LOST_STEPS), 0x73);
  EXPECT_EQ(chip::info(Reg::PWMCONF).reset, 0x00050480u);
  EXPECT_EQ(chip::kRegisterCount, 31u);
}

TEST(tmc2130_regmap, dynamic_lookup_is_a_typed_miss) {
  EXPECT_EQ(chip::find_register("IHOLD_IRUN"), Reg::IHOLD_IRUN);
  EXPECT_EQ(chip::find_register(std::uint8_t{0x6C}), Reg::CHOPCONF);
  EXPECT_FALSE(chip::find_register("IHOLD_RUN").has_value());
  EXPECT_FALSE(chip::find_register(std::uint8_t{0x05}).has_value());
  EXPECT_EQ(chip::find_field(Reg::CHOPCONF, "MRES"), Field::CHOPCONF_MRES);
  EXPECT_FALSE(chip::find_field(Reg::CHOPCONF, "IRUN").has_value());
}

TEST(tmc2130_fields, out_of_range_is_rejected_not_masked) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  b.clear();
  const auto before = b.driver.shadow(Reg::IHOLD_IRUN);
  auto r = b.driver.set<Field::IHOLD_IRUN_IRUN>(32);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), chip::Error::ValueOutOfRange);
  EXPECT_EQ(b.driver.set(Field::COOLCONF_sgt, -65).error(), chip::Error::ValueOutOfRange);
  EXPECT_EQ(b.driver.set(Field::CHOPCONF_MRES, 9).error(), chip::Error::ValueOutOfRange);
  EXPECT_EQ(b.driver.set(Field::XDIRECT_COIL_A, -256).error(), chip::Error::ValueOutOfRange);
  EXPECT_EQ(b.driver.set(Field::IHOLD_IRUN_IHOLD, -1).error(), chip::Error::ValueOutOfRange);
  EXPECT_TRUE(b.mosi.empty());
  EXPECT_EQ(b.driver.shadow(Reg::IHOLD_IRUN), before);
  EXPECT_FALSE(chip::field_set(0, Field::TPOWERDOWN_TPOWERDOWN, 256));
}

TEST(tmc2130_fields, batch_errors_leave_everything_unchanged) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  b.clear();
  EXPECT_EQ(b.driver.update(Reg::IHOLD_IRUN, {{Field::IHOLD_IRUN_IRUN, 5}, {Field::CHOPCONF_TOFF, 3}}).error(),
            chip::Error::FieldNotInRegister);
  EXPECT_EQ(b.driver.update(Reg::IHOLD_IRUN, {{Field::IHOLD_IRUN_IRUN, 5}, {Field::IHOLD_IRUN_IRUN, 6}}).error(),
            chip::Error::DuplicateField);
  EXPECT_EQ(b.driver.update(Reg::IHOLD_IRUN, {{Field::IHOLD_IRUN_IRUN, 5}, {Field::IHOLD_IRUN_IHOLD, 99}}).error(),
            chip::Error::ValueOutOfRange);
  EXPECT_EQ(b.driver.set(Field::DRV_STATUS_stst, 1).error(), chip::Error::NotWritable);
  EXPECT_EQ(b.driver.write(Reg::GSTAT, 1).error(), chip::Error::NotWritable);
  EXPECT_TRUE(b.mosi.empty());
  EXPECT_TRUE(b.chip_matches_shadows());
}

// TMCStepper #43: a getter of a write-only register must not touch the shadow.
TEST(tmc2130_driver, write_only_getter_keeps_shadow_and_sends_nothing) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.set<Field::PWMCONF_PWM_GRAD>(77));
  b.clear();
  EXPECT_EQ(*b.driver.get<Field::PWMCONF_PWM_GRAD>(), 77);
  EXPECT_EQ(*b.driver.get<Field::PWMCONF_PWM_AMPL>(), 128);  // reset value survives
  EXPECT_TRUE(b.mosi.empty());
  ASSERT_TRUE(b.driver.set<Field::PWMCONF_freewheel>(2));
  EXPECT_EQ(chip::field_get(b.device.chip_register(Reg::PWMCONF), Field::PWMCONF_PWM_GRAD), 77);
  EXPECT_EQ(chip::field_get(b.device.chip_register(Reg::PWMCONF), Field::PWMCONF_PWM_AMPL), 128);
}

TEST(tmc2130_driver, readable_register_rmw_reads_chip_and_verifies) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_TOFF>(3));
  b.clear();
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_MRES>(4));
  // read (2 transfers), write, read back (2 transfers)
  ASSERT_EQ(b.mosi.size(), 5u);
  EXPECT_EQ(b.mosi[2][0], 0x80 | 0x6C);
  EXPECT_EQ(chip::data_of(b.mosi[2]), 0x04000003u);
  EXPECT_EQ(*b.driver.get<Field::CHOPCONF_TOFF>(), 3);
}

TEST(tmc2130_driver, readback_mismatch_is_retried_then_reported) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  b.device.corrupt_writes(Reg::CHOPCONF, 0x1, chip::Driver::kMaxWriteAttempts - 1);
  b.clear();
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_TOFF>(4));
  EXPECT_EQ(b.device.writes_of(Reg::CHOPCONF), chip::Driver::kMaxWriteAttempts);
  EXPECT_EQ(chip::field_get(b.device.chip_register(Reg::CHOPCONF), Field::CHOPCONF_TOFF), 4);

  b.device.corrupt_writes(Reg::CHOPCONF, 0x1, chip::Driver::kMaxWriteAttempts);
  b.clear();
  const auto r = b.driver.set<Field::CHOPCONF_TOFF>(6);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), chip::Error::ReadbackMismatch);
  EXPECT_EQ(b.device.writes_of(Reg::CHOPCONF), chip::Driver::kMaxWriteAttempts);
}

TEST(tmc2130_driver, bus_failure_leaves_shadow_unchanged) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  b.bus_fails = true;
  const auto r = b.driver.set<Field::IHOLD_IRUN_IRUN>(20);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), chip::Error::BusFailure);
  EXPECT_EQ(chip::field_get(b.driver.shadow(Reg::IHOLD_IRUN), Field::IHOLD_IRUN_IRUN), 0);
}

TEST(tmc2130_driver, status_byte_reaches_the_caller) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  b.device.set_input(Reg::DRV_STATUS, 0x81000000u);  // stst + stallGuard
  b.device.set_input(Reg::GSTAT, 0x2u);               // drv_err
  const auto r = b.driver.set<Field::TPOWERDOWN_TPOWERDOWN>(10);
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, (chip::SpiStatus{false, true, true, true}));
  EXPECT_EQ(b.driver.last_status(), (chip::SpiStatus{false, true, true, true}));
}

TEST(tmc2130_driver, reset_is_detected_and_every_shadow_rewritten) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.update(Reg::IHOLD_IRUN, {{Field::IHOLD_IRUN_IHOLD, 3}, {Field::IHOLD_IRUN_IRUN, 12}}));
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_MRES>(4));
  ASSERT_TRUE(b.driver.set<Field::COOLCONF_sgt>(-7));
  const unsigned before = b.driver.resets_recovered();
  b.device.power_cycle();
  ASSERT_FALSE(b.chip_matches_shadows());
  ASSERT_TRUE(b.driver.set<Field::TPOWERDOWN_TPOWERDOWN>(20));  // reply carries reset_flag
  EXPECT_EQ(b.driver.resets_recovered(), before + 1);
  EXPECT_TRUE(b.chip_matches_shadows());
  EXPECT_EQ(b.device.chip_register(Reg::GSTAT), 0u);

  b.device.power_cycle();
  ASSERT_TRUE(b.driver.check_reset());
  EXPECT_EQ(b.driver.resets_recovered(), before + 2);
  EXPECT_TRUE(b.chip_matches_shadows());
}

// The supply bounces: a second reset lands in the middle of the re-initialisation. The
// driver must notice (GSTAT is cleared before the rewrite) and go round again.
TEST(tmc2130_driver, reset_during_reinit_is_not_lost) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.set<Field::IHOLD_IRUN_IRUN>(12));
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_TOFF>(4));
  b.device.power_cycle();
  b.device.power_cycle_after(8);  // inside the rewrite of ~20 registers
  ASSERT_TRUE(b.driver.check_reset());
  EXPECT_TRUE(b.chip_matches_shadows());
  EXPECT_EQ(b.device.chip_register(Reg::GSTAT), 0u);
}

// Every write of IHOLD_IRUN during re-init is followed by another reset: bounded rounds,
// then a typed error instead of an endless loop.
struct ResetOnIholdIrun {
  Device device;
  static bool spi(void* context, const chip::Datagram& tx, chip::Datagram& rx) {
    auto* self = static_cast<ResetOnIholdIrun*>(context);
    rx = self->device.transfer(tx);
    const auto req = chip::decode_request(tx);
    if (req.write && req.address == chip::address(Reg::IHOLD_IRUN)) self->device.power_cycle_after(2);
    return true;
  }
};

TEST(tmc2130_driver, chip_that_keeps_resetting_is_reported) {
  ResetOnIholdIrun rig;
  chip::Driver d(chip::SpiPort{&ResetOnIholdIrun::spi, &rig});
  const auto r = d.init();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), chip::Error::ChipKeepsResetting);
  EXPECT_EQ(rig.device.writes_of(Reg::IHOLD_IRUN), chip::Driver::kMaxWriteAttempts);
}

TEST(tmc2130_driver, read_right_after_reset_returns_restored_value) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_TOFF>(5));
  b.device.power_cycle();
  EXPECT_EQ(*b.driver.get<Field::CHOPCONF_TOFF>(), 5);
  EXPECT_TRUE(b.chip_matches_shadows());
}

// A reset seen during the read of a readable register's RMW must not make the reset
// contents the base of the write.
TEST(tmc2130_driver, reset_during_readable_rmw_keeps_other_fields) {
  Bench b;
  ASSERT_TRUE(b.driver.init());
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_TOFF>(5));
  b.device.power_cycle();
  ASSERT_TRUE(b.driver.set<Field::CHOPCONF_MRES>(2));
  EXPECT_EQ(chip::field_get(b.device.chip_register(Reg::CHOPCONF), Field::CHOPCONF_TOFF), 5);
  EXPECT_EQ(chip::field_get(b.device.chip_register(Reg::CHOPCONF), Field::CHOPCONF_MRES), 2);
}

TEST(tmc2130_model, pipelined_read_and_gstat_clear_on_read) {
  Device d;
  const auto r1 = d.transfer(chip::encode({false, 0x01, 0}));
  EXPECT_EQ(r1[0] & 1, 1);                // reset flag in the status byte
  const auto r2 = d.transfer(chip::encode({false, 0x01, 0}));
  EXPECT_EQ(chip::data_of(r2), 1u);      // GSTAT as latched by the first read
  EXPECT_EQ(r2[0] & 1, 0);               // ... which cleared it
  d.transfer(chip::encode({true, 0x10, 0x00070C03}));
  d.transfer(chip::encode({false, 0x10, 0}));
  EXPECT_EQ(chip::data_of(d.transfer(chip::encode({false, 0x10, 0}))), 0u);  // write-only
  EXPECT_EQ(d.chip_register(Reg::IHOLD_IRUN), 0x00070C03u);
  d.transfer(chip::encode({true, 0x6C, 0xFFFFFFFF}));
  EXPECT_EQ(d.chip_register(Reg::CHOPCONF), chip::implemented_mask(Reg::CHOPCONF));
}

// Equation (7-1) against a double-precision oracle: the integer result is the true value
// rounded to nearest (the irrational value is never within 1e-6 of a .5 here).
TEST(tmc2130_current, matches_equation_7_1_for_every_cs) {
  namespace cur = chip::current;
  EXPECT_EQ(*cur::current_ma(12, false, cur::kThesisRsenseMohm), 707u);
  EXPECT_EQ(*cur::current_ma(31, false, cur::kThesisRsenseMohm), 1741u);
  EXPECT_EQ(*cur::current_ma(12, true, cur::kThesisRsenseMohm), 398u);
  for (unsigned r : {1u, 47u, 75u, 100u, 110u, 150u, 220u, 330u, 1000u}) {
    for (bool vs : {false, true}) {
      for (unsigned cs = 0; cs <= 31; ++cs) {
        const double exact = (cs + 1.0) / 32.0 * (vs ? 180.0 : 320.0) / ((r + 20.0) / 1000.0) / std::sqrt(2.0);
        const auto got = cur::current_ma(static_cast<std::uint8_t>(cs), vs, r);
        ASSERT_TRUE(got);
        EXPECT_EQ(*got, static_cast<unsigned>(std::floor(exact + 0.5))) << "cs " << cs << " r " << r;
      }
    }
  }
  EXPECT_EQ(cur::current_ma(32, false, 110).error(), chip::Error::CurrentOutOfRange);
  EXPECT_EQ(cur::current_ma(1, false, 0).error(), chip::Error::CurrentOutOfRange);
}

TEST(tmc2130_current, cs_for_current_is_largest_not_exceeding) {
  namespace cur = chip::current;
  EXPECT_EQ(*cur::cs_for_current(707, false, 110), 11);  // CS 12 is 707.107 mA > 707
  EXPECT_EQ(*cur::cs_for_current(708, false, 110), 12);
  EXPECT_EQ(*cur::cs_for_current(5000, false, 110), 31);
  EXPECT_EQ(cur::cs_for_current(10, false, 110).error(), chip::Error::CurrentOutOfRange);
  EXPECT_EQ(cur::cs_for_current(20000, false, 110).error(), chip::Error::CurrentOutOfRange);
  for (unsigned r : {47u, 110u, 220u}) {
    for (bool vs : {false, true}) {
      for (unsigned ma = 0; ma <= 3000; ma += 7) {
        int best = -1;
        for (int cs = 0; cs <= 31; ++cs) {
          const double exact = (cs + 1.0) / 32.0 * (vs ? 180.0 : 320.0) / ((r + 20.0) / 1000.0) / std::sqrt(2.0);
          if (exact <= ma) best = cs;
        }
        const auto got = cur::cs_for_current(ma, vs, r);
        if (best < 0) {
          EXPECT_FALSE(got) << ma;
        } else {
          ASSERT_TRUE(got) << ma;
          EXPECT_EQ(int{*got}, best) << "ma " << ma << " r " << r;
        }
      }
    }
  }
}

TEST(tmc2130_text, decode_golden_datagram) {
  const auto d = ap::model::xy_tmc2130::parse_datagram({"90", "00", "07", "0C", "03"});
  ASSERT_TRUE(d);
  EXPECT_EQ(ap::model::xy_tmc2130::decode_datagram(*d, false),
            "write IHOLD_IRUN (0x10) data 0x00070C03\n  IHOLD=3 IRUN=12 IHOLDDELAY=7\n");
  EXPECT_EQ(ap::model::xy_tmc2130::parse_datagram({"0x90,0x00,0x07,0x0C,0x03"}), d);
  EXPECT_EQ(ap::model::xy_tmc2130::parse_datagram({"9000070C03"}), d);
  EXPECT_FALSE(ap::model::xy_tmc2130::parse_datagram({"90", "00", "07", "0C"}));
  EXPECT_FALSE(ap::model::xy_tmc2130::parse_datagram({"90", "00", "07", "0C", "zz"}));
}

// docs/tmc2130.md carries the map between two markers; it must equal the table.
TEST(tmc2130_docs, register_map_in_docs_matches_table) {
  std::ifstream in(std::string(AP_SOURCE_DIR) + "/docs/tmc2130.md");
  ASSERT_TRUE(in) << "docs/tmc2130.md missing";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const std::string begin = "<!-- regmap:begin (generated: axisproof regs --format md) -->\n";
  const std::string end = "<!-- regmap:end -->";
  const auto b = doc.find(begin);
  const auto e = doc.find(end);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()),
            ap::model::xy_tmc2130::register_map(ap::model::xy_tmc2130::MapFormat::Markdown));
}

}  // namespace

// The power stage as the datasheet states it, written as raw datagrams (not through the
// firmware's driver): 5.5 CHOPCONF (0x6C) TOFF bits 3..0, %0000 = driver disabled; MRES bits
// 27..24, %0000 = 256 microsteps ... %1000 = full step; pin DRV_ENN high = outputs off.
namespace {
chip::Datagram write_chopconf(std::uint32_t v) {
  return {0x80 | 0x6C, static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16),
          static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)};
}
}  // namespace

TEST(tmc2130_power_stage, reset_chip_does_not_turn_the_motor) {
  ap::model::xy_tmc2130::Device d;
  EXPECT_FALSE(d.power_stage_on());
  EXPECT_EQ(d.step(100, 1), 0);
  EXPECT_EQ(d.microsteps(), 256);  // MRES = 0 after reset
}

TEST(tmc2130_power_stage, toff_nonzero_turns_the_motor_by_mres) {
  ap::model::xy_tmc2130::Device d;
  (void)d.transfer(write_chopconf(0x04000003u));  // MRES 4, TOFF 3
  EXPECT_TRUE(d.power_stage_on());
  EXPECT_EQ(d.microsteps(), 16);
  EXPECT_EQ(d.step(16, 1), 256);  // 16 edges at 1/16 = one full step
  EXPECT_EQ(d.step(3, -1), -48);
  (void)d.transfer(write_chopconf(0x08000001u));  // full step, TOFF 1
  EXPECT_EQ(d.step(2, 1), 512);
  (void)d.transfer(write_chopconf(0x08000000u));  // TOFF back to 0: off again
  EXPECT_FALSE(d.power_stage_on());
  EXPECT_EQ(d.step(2, 1), 0);
}

TEST(tmc2130_power_stage, drv_enn_high_switches_the_outputs_off) {
  ap::model::xy_tmc2130::Device d;
  (void)d.transfer(write_chopconf(0x00000003u));
  d.set_drv_enn(true);
  EXPECT_FALSE(d.power_stage_on());
  EXPECT_EQ(d.step(10, 1), 0);
  d.set_drv_enn(false);
  EXPECT_EQ(d.step(10, 1), 10);  // 256 microsteps: one 1/256 step per edge
}

TEST(tmc2130_power_stage, a_power_cycle_switches_the_chopper_off) {
  ap::model::xy_tmc2130::Device d;
  (void)d.transfer(write_chopconf(0x04000003u));
  d.power_cycle();
  EXPECT_FALSE(d.power_stage_on());
}

// Standstill and current (datasheet 5.5 DRV_STATUS.stst: 2^20 clocks after the last step;
// 5.2 IHOLD_IRUN / TPOWERDOWN: the current falls from IRUN to IHOLD after TPOWERDOWN * 2^18
// clocks, one step per IHOLDDELAY * 2^18 clocks), at the 12 MHz nominal clock: 2^20 clocks =
// 87.4 ms, 2^18 clocks = 21.8 ms.
namespace {
chip::Datagram write_reg(std::uint8_t addr, std::uint32_t v) {
  return {static_cast<std::uint8_t>(0x80 | addr), static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16),
          static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)};
}
}  // namespace

TEST(tmc2130_power_stage, standstill_and_hold_current_after_the_last_step) {
  ap::model::xy_tmc2130::Device d;
  (void)d.transfer(write_chopconf(0x04000003u));
  (void)d.transfer(write_reg(0x10, (6u << 16) | (16u << 8) | 8u));  // IHOLDDELAY 6, IRUN 16, IHOLD 8
  (void)d.transfer(write_reg(0x11, 10u));                             // TPOWERDOWN 10
  EXPECT_TRUE(d.standstill());  // nothing stepped since power-up
  (void)d.step(5, 1);
  EXPECT_FALSE(d.standstill());
  EXPECT_EQ(d.current_scale(), 16);
  d.elapse_us(87'000);
  EXPECT_FALSE(d.standstill());
  d.elapse_us(1'000);
  EXPECT_TRUE(d.standstill());  // 88 ms > 87.4 ms
  d.elapse_us(130'000);         // 218 ms: TPOWERDOWN (218.45 ms) not yet over
  EXPECT_EQ(d.current_scale(), 16);
  d.elapse_us(1'000);           // 219 ms: the first step down
  EXPECT_EQ(d.current_scale(), 15);
  d.elapse_us(130'000);         // 349 ms: 130.6 ms into the fall, one IHOLDDELAY period is 131.1 ms
  EXPECT_EQ(d.current_scale(), 15);
  d.elapse_us(1'000);           // 350 ms: 131.6 ms in, the second step down
  EXPECT_EQ(d.current_scale(), 14);
  d.elapse_us(2'000'000);
  EXPECT_EQ(d.current_scale(), 8);  // IHOLD, no lower
  // DRV_STATUS reads stst and CS_ACTUAL (bits 20..16).
  EXPECT_EQ(d.chip_register(chip::Reg::DRV_STATUS), 0x80000000u | (8u << 16));
  (void)d.step(1, 1);
  EXPECT_EQ(d.chip_register(chip::Reg::DRV_STATUS), 16u << 16);
}

TEST(tmc2130_power_stage, overtemperature_and_a_short_switch_the_bridges_off) {
  ap::model::xy_tmc2130::Device d;
  (void)d.transfer(write_chopconf(0x00000003u));
  d.set_input(Reg::DRV_STATUS, 1u << 25);  // ot
  EXPECT_FALSE(d.power_stage_on());
  d.set_input(Reg::DRV_STATUS, 0);
  EXPECT_TRUE(d.power_stage_on());         // ot clears with the temperature
  d.set_input(Reg::DRV_STATUS, 1u << 27);  // s2ga
  d.set_input(Reg::DRV_STATUS, 0);
  EXPECT_FALSE(d.power_stage_on()) << "a short stays latched";
  EXPECT_EQ(d.step(4, 1), 0);
  (void)d.transfer(write_chopconf(0x00000000u));  // TOFF = 0 clears it
  (void)d.transfer(write_chopconf(0x00000003u));
  EXPECT_TRUE(d.power_stage_on());
  d.set_input(Reg::DRV_STATUS, 1u << 28);  // s2gb, cleared by DRV_ENN this time
  d.set_input(Reg::DRV_STATUS, 0);
  d.set_drv_enn(true);
  (void)d.step(0, 1);
  d.set_drv_enn(false);
  EXPECT_TRUE(d.power_stage_on());
}

TEST(tmc2130_power_stage, diag_outputs_follow_gconf) {
  ap::model::xy_tmc2130::Device d;
  d.set_input(Reg::DRV_STATUS, (1u << 26) | (1u << 24));  // otpw, stallGuard
  EXPECT_FALSE(d.diag0_asserted());
  EXPECT_FALSE(d.diag1_asserted());
  EXPECT_TRUE(d.diag0_level());  // open drain, released: high
  (void)d.transfer(write_reg(0x00, (1u << 6) | (1u << 8)));  // diag0_otpw, diag1_stall
  EXPECT_TRUE(d.diag0_asserted());
  EXPECT_TRUE(d.diag1_asserted());
  EXPECT_FALSE(d.diag0_level());  // active low
  EXPECT_FALSE(d.diag1_level());
  (void)d.transfer(write_reg(0x00, (1u << 6) | (1u << 8) | (1u << 12) | (1u << 13)));  // push-pull: active high
  EXPECT_TRUE(d.diag0_level());
  EXPECT_TRUE(d.diag1_level());
  d.set_input(Reg::DRV_STATUS, 0);
  EXPECT_FALSE(d.diag0_asserted());
  EXPECT_FALSE(d.diag1_asserted());
  (void)d.transfer(write_reg(0x00, 1u << 5));  // diag0_error
  d.set_input(Reg::DRV_STATUS, 1u << 25);      // ot
  EXPECT_TRUE(d.diag0_asserted());
}

// Two independent readings of the datasheet must agree: the firmware's register table
// (core/xy/tmc2130/regmap.hpp, the code under test) and the device model's own table
// (models/xy/tmc2130/datasheet.hpp, written from the datasheet without looking at the firmware).
// The model's value is the expected one. A failure here is a disagreement for a human to
// settle against the datasheet; do not make it pass by copying one table into the other.
namespace {
namespace ds = ap::model::xy_tmc2130::datasheet;

std::string hex32(std::uint32_t v) {
  std::ostringstream o;
  o << "0x" << std::hex << std::uppercase;
  o.width(8);
  o.fill('0');
  o << v;
  return o.str();
}
}  // namespace

TEST(tmc2130_datasheet, the_same_registers_at_the_same_addresses) {
  EXPECT_EQ(chip::kRegisterCount, ds::kRegisters.size());
  for (const auto& fw : chip::kRegisters) {
    const ds::RegisterFact* f = ds::fact(chip::address(fw.reg));
    ASSERT_NE(f, nullptr) << fw.name << ": the firmware puts it at " << hex32(chip::address(fw.reg))
                          << ", the datasheet has no register there";
    EXPECT_EQ(fw.name, f->name) << "address " << hex32(f->address) << ": firmware " << fw.name << ", datasheet "
                                << f->name;
  }
  for (const auto& f : ds::kRegisters) {
    const auto idx = chip::register_index(f.address);
    EXPECT_TRUE(idx.has_value()) << f.name << " (datasheet address " << hex32(f.address)
                                 << ") is missing from the firmware table";
    if (!idx) continue;
    EXPECT_EQ(chip::address(chip::kRegisters[*idx].reg), f.address) << f.name;
  }
}

TEST(tmc2130_datasheet, access_agrees) {
  for (const auto& f : ds::kRegisters) {
    const auto idx = chip::register_index(f.address);
    if (!idx) continue;  // reported by the_same_registers_at_the_same_addresses
    const auto& fw = chip::kRegisters[*idx];
    EXPECT_EQ(chip::access_name(fw.access), ds::access_name(f.access))
        << f.name << " access: firmware " << chip::access_name(fw.access) << ", datasheet "
        << ds::access_name(f.access);
    EXPECT_EQ(chip::readable(fw.reg), ds::readable(f.access)) << f.name << " readable";
    EXPECT_EQ(chip::writable(fw.reg), ds::writable(f.access)) << f.name << " writable";
    EXPECT_EQ(fw.access == chip::Access::RC, ds::clears_on_read(f.access)) << f.name << " clear on read";
  }
}

TEST(tmc2130_datasheet, reset_value_agrees) {
  for (const auto& f : ds::kRegisters) {
    const auto idx = chip::register_index(f.address);
    if (!idx) continue;
    const auto& fw = chip::kRegisters[*idx];
    EXPECT_EQ(fw.reset, f.reset) << f.name << " reset: firmware " << hex32(fw.reset) << ", datasheet "
                                 << hex32(f.reset);
  }
}

TEST(tmc2130_datasheet, implemented_mask_agrees) {
  for (const auto& f : ds::kRegisters) {
    const auto idx = chip::register_index(f.address);
    if (!idx) continue;
    const auto& fw = chip::kRegisters[*idx];
    const std::uint32_t m = chip::implemented_mask(fw.reg);
    EXPECT_EQ(m, f.implemented) << f.name << " implemented bits: firmware " << hex32(m) << ", datasheet "
                                << hex32(f.implemented) << " (differ in " << hex32(m ^ f.implemented) << ")";
  }
}

// The model behaves by its own table: a fresh chip holds the datasheet's reset values, a read
// returns 0 exactly for the write-only registers, and an all-ones write keeps exactly the
// implemented bits (raw datagrams, no firmware driver in between).
TEST(tmc2130_datasheet, the_model_follows_its_datasheet_table) {
  for (const auto& f : ds::kRegisters) {
    ap::model::xy_tmc2130::Device d;
    const auto reg = static_cast<chip::Reg>(f.address);  // chip::Reg's value is the SPI address
    EXPECT_EQ(d.chip_register(reg), f.reset) << f.name << " after power-up";
    if (f.address == ds::addr::GSTAT) continue;  // its read clears it; see tmc2130_model
    (void)d.transfer(chip::encode({false, f.address, 0}));
    const std::uint32_t got = chip::data_of(d.transfer(chip::encode({false, f.address, 0})));
    EXPECT_EQ(got, ds::readable(f.access) ? f.reset : 0u) << f.name << " read after power-up";
    if (!ds::writable(f.access)) continue;
    (void)d.transfer(chip::encode({true, f.address, 0xFFFFFFFFu}));
    EXPECT_EQ(d.chip_register(reg), f.implemented) << f.name << " after writing all ones";
  }
}
