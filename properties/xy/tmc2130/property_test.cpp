// TMC2130 properties against the device model. Generators draw any writable field, any
// in-range value and random prior register contents, so the claims hold for the whole map,
// not for the fields someone thought of.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <vector>

#include "harness.hpp"

namespace {

using namespace tmc_test;
using chip::Field;
using chip::Reg;

std::vector<Field> writable_fields() {
  std::vector<Field> out;
  for (const auto& f : chip::kFields) {
    if (chip::writable(f.reg)) out.push_back(f.field);
  }
  return out;
}

rc::Gen<Field> gen_writable_field() { return rc::gen::elementOf(writable_fields()); }

rc::Gen<std::int64_t> gen_value(Field f) {
  const auto& fi = chip::info(f);
  // Edges are where masking bugs live; plain uniform draws rarely hit them.
  return rc::gen::oneOf(rc::gen::inRange<std::int64_t>(fi.min, fi.max + 1),
                        rc::gen::elementOf(std::vector<std::int64_t>{fi.min, fi.max, 0 < fi.min ? fi.min : 0}));
}

chip::FieldValue gen_assignment() {
  const Field f = *gen_writable_field();
  return {f, *gen_value(f)};
}

// Random earlier history, so the "other" bits are not all zero.
void scramble(Bench& b) {
  const auto n = *rc::gen::inRange(0, 12);
  for (int i = 0; i < n; ++i) {
    const auto a = gen_assignment();
    RC_ASSERT(b.driver.set(a.field, a.value));
  }
}

RC_GTEST_PROP(tmc2130_props, set_changes_exactly_that_field_on_the_chip, ()) {
  Bench b;
  RC_ASSERT(b.driver.init());
  scramble(b);
  const auto a = gen_assignment();
  const auto& fi = chip::info(a.field);
  const std::uint32_t before = b.device.chip_register(fi.reg);
  RC_ASSERT(b.driver.set(a.field, a.value));
  const std::uint32_t after = b.device.chip_register(fi.reg);
  RC_ASSERT(((before ^ after) & ~fi.mask) == 0u);
  RC_ASSERT(chip::field_get(after, a.field) == a.value);
  RC_ASSERT(*b.driver.get(a.field) == a.value);
  RC_ASSERT(b.chip_matches_shadows());
}

RC_GTEST_PROP(tmc2130_props, batch_equals_one_by_one, ()) {
  const Reg reg = *rc::gen::elementOf(std::vector<Reg>{Reg::GCONF, Reg::IHOLD_IRUN, Reg::XDIRECT, Reg::MSLUTSEL,
                                                        Reg::MSLUTSTART, Reg::CHOPCONF, Reg::COOLCONF,
                                                        Reg::DCCTRL, Reg::PWMCONF, Reg::ENCM_CTRL});
  const auto& ri = chip::info(reg);
  std::vector<chip::FieldValue> batch;
  for (std::size_t i = ri.first_field; i < std::size_t{ri.first_field} + ri.field_count; ++i) {
    if (*rc::gen::arbitrary<bool>()) batch.push_back({chip::kFields[i].field, *gen_value(chip::kFields[i].field)});
  }
  Bench one, many;
  RC_ASSERT(one.driver.init());
  RC_ASSERT(many.driver.init());
  one.clear();
  RC_ASSERT(one.driver.update(reg, batch));
  for (const auto& fv : batch) RC_ASSERT(many.driver.set(fv.field, fv.value));
  RC_ASSERT(one.device.chip_register(reg) == many.device.chip_register(reg));
  RC_ASSERT(one.driver.shadow(reg) == many.driver.shadow(reg));
  RC_ASSERT(one.device.writes_of(reg) == 1u);  // a single datagram, as Obr. 7-12 demands
}

RC_GTEST_PROP(tmc2130_props, datagram_round_trips, (std::uint8_t addr, std::uint32_t data, bool write)) {
  const chip::Request req{write, static_cast<std::uint8_t>(addr & 0x7F), data};
  const chip::Datagram d = chip::encode(req);
  RC_ASSERT(chip::decode_request(d) == req);
  RC_ASSERT(d[0] == static_cast<std::uint8_t>(req.address | (write ? 0x80 : 0)));
  RC_ASSERT(d[1] == static_cast<std::uint8_t>(data >> 24));  // MSB first
  const chip::Datagram any{addr, static_cast<std::uint8_t>(data), static_cast<std::uint8_t>(data >> 8),
                           static_cast<std::uint8_t>(data >> 16), static_cast<std::uint8_t>(data >> 24)};
  RC_ASSERT(chip::encode(chip::decode_request(any)) == any);
  const auto status = static_cast<std::uint8_t>(addr & 0x0F);
  RC_ASSERT(chip::encode_status(chip::decode_status(status)) == status);
}

RC_GTEST_PROP(tmc2130_props, write_only_rmw_issues_no_read, ()) {
  Bench b;
  RC_ASSERT(b.driver.init());
  scramble(b);
  std::vector<Field> wo;
  for (const auto& f : chip::kFields) {
    if (chip::info(f.reg).access == chip::Access::W) wo.push_back(f.field);
  }
  const Field f = *rc::gen::elementOf(wo);
  const auto v = *gen_value(f);
  b.clear();
  RC_ASSERT(b.driver.set(f, v));
  RC_ASSERT(b.reads() == 0u);
  RC_ASSERT(b.mosi.size() == 1u);
  RC_ASSERT(*b.driver.get(f) == v);
  RC_ASSERT(b.mosi.size() == 1u);  // the getter went to the shadow, not the bus
}

RC_GTEST_PROP(tmc2130_props, after_reset_and_reinit_chip_equals_shadows, ()) {
  Bench b;
  RC_ASSERT(b.driver.init());
  scramble(b);
  b.device.power_cycle();
  // Detection either through the status byte of the next access or by polling GSTAT.
  if (*rc::gen::arbitrary<bool>()) {
    const auto a = gen_assignment();
    RC_ASSERT(b.driver.set(a.field, a.value));
  } else {
    RC_ASSERT(b.driver.check_reset());
  }
  RC_ASSERT(b.chip_matches_shadows());
  RC_ASSERT(b.device.chip_register(Reg::GSTAT) == 0u);
}

RC_GTEST_PROP(tmc2130_props, out_of_range_changes_nothing, ()) {
  Bench b;
  RC_ASSERT(b.driver.init());
  scramble(b);
  const Field f = *gen_writable_field();
  const auto& fi = chip::info(f);
  const auto off = *rc::gen::inRange<std::int64_t>(1, std::int64_t{1} << 33);
  const std::int64_t bad = *rc::gen::arbitrary<bool>() ? fi.max + off : fi.min - off;
  const std::uint32_t chip_before = b.device.chip_register(fi.reg);
  const std::uint32_t shadow_before = b.driver.shadow(fi.reg);
  b.clear();
  const auto r = b.driver.set(f, bad);
  RC_ASSERT(!r);
  RC_ASSERT(r.error() == chip::Error::ValueOutOfRange);
  RC_ASSERT(b.mosi.empty());
  RC_ASSERT(b.device.chip_register(fi.reg) == chip_before);
  RC_ASSERT(b.driver.shadow(fi.reg) == shadow_before);
}

RC_GTEST_PROP(tmc2130_props, pure_field_set_get, (std::uint32_t word)) {
  const Field f = *rc::gen::elementOf(std::vector<Field>([] {
    std::vector<Field> all;
    for (const auto& fi : chip::kFields) all.push_back(fi.field);
    return all;
  }()));
  const auto v = *gen_value(f);
  const auto next = chip::field_set(word, f, v);
  RC_ASSERT(next);
  RC_ASSERT(((*next ^ word) & ~chip::info(f).mask) == 0u);
  RC_ASSERT(chip::field_get(*next, f) == v);
}

}  // namespace
