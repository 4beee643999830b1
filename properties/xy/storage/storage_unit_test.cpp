// Example-based checks of the FRAM map, the record codec, the MB85RS256B model and the store.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "core/xy/storage/crc32.hpp"
#include "core/xy/storage/fram_device.hpp"
#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;

namespace {

std::uint8_t id_of(ParamId id) { return static_cast<std::uint8_t>(id); }

// A bus that records every frame on its way to the model, to check the bytes on the wire.
struct Tap {
  Mb85rs256b* chip;
  std::vector<std::vector<std::uint8_t>> frames;
  SpiBus bus() {
    return SpiBus{[](void* ctx, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
                    auto* self = static_cast<Tap*>(ctx);
                    self->frames.emplace_back(tx.begin(), tx.end());
                    return self->chip->transfer(tx, rx);
                  },
                  this};
  }
};

ParameterSet variant_set() {
  ParameterSet s = defaults();
  s.max_acceleration_um_s2 = 5000;
  s.fast_speed_um_s = 12000;
  s.soft_min_x_um = -1500;
  s.stallguard_threshold = -7;
  s.step_count_y = -123456;
  return s;
}

void write_record(Mb85rs256b& chip, std::size_t copy, const ParameterSet& s, std::uint32_t seq) {
  RecordBytes r{};
  encode_record(s, seq, r);
  std::memcpy(chip.memory().data() + kCopyBase[copy], r.data(), r.size());
}

void refresh_crc(Mb85rs256b& chip, std::size_t copy) {
  std::uint8_t* base = chip.memory().data() + kCopyBase[copy];
  put_le(std::span<std::uint8_t>(base, kRecordSize), kCrcOffset, 4,
         crc32(std::span<const std::uint8_t>(base, kCrcOffset)));
}

}  // namespace

// ---------------------------------------------------------------- map and codec

TEST(storage_map, names_a_real_part_and_fits_it) {
  EXPECT_EQ(kChip.part, "Fujitsu MB85RS256B");
  EXPECT_EQ(kChip.size_bytes, 32768U);
  EXPECT_TRUE(regions_disjoint(address_map()));
  EXPECT_TRUE(regions_fit_chip(address_map()));
  EXPECT_EQ(address_map().size(), kItemCount * kCopyCount);
}

// The checks themselves must be able to fail, or the static_asserts prove nothing.
TEST(storage_map, disjointness_check_detects_an_overlap_and_a_misfit) {
  std::array<Region, 2> overlap{{{ParamId::MaxAcceleration, 0, 0x0000, 4}, {ParamId::FastSpeed, 0, 0x0003, 4}}};
  std::array<Region, 2> touching{{{ParamId::MaxAcceleration, 0, 0x0000, 4}, {ParamId::FastSpeed, 0, 0x0004, 4}}};
  std::array<Region, 1> outside{{{ParamId::MaxAcceleration, 0, 32766, 4}}};
  EXPECT_FALSE(regions_disjoint(overlap));
  EXPECT_TRUE(regions_disjoint(touching));
  EXPECT_FALSE(regions_fit_chip(outside));
}

TEST(storage_crc, matches_the_standard_check_value) {
  const char* s = "123456789";
  EXPECT_EQ(crc32(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(s), 9)), 0xCBF43926U);
}

TEST(storage_golden, thesis_max_acceleration_20000_at_0x0000_lsb_first) {
  ParameterSet s = defaults();
  s.max_acceleration_um_s2 = 20000;
  RecordBytes r{};
  encode_record(s, 1, r);
  EXPECT_EQ(r[0], 0x20);
  EXPECT_EQ(r[1], 0x4E);
  EXPECT_EQ(r[2], 0x00);
  EXPECT_EQ(r[3], 0x00);
}

// The same bytes end-to-end: a PARAM_SET of 20000 through the store, on the SPI wire and in
// the chip at 0x0000 (thesis §9.2, Obr. 9-4). The frames of one save are the protocol of
// docs/storage.md ("Save protocol"): WREN, WRITE of the spoil key (the complement of the new
// record's CRC) into the target's CRC field, WREN, WRITE of the whole record, READ of it.
TEST(storage_golden, thesis_write_on_the_wire_and_in_the_chip) {
  auto chip = std::make_unique<Mb85rs256b>();
  Tap tap{chip.get(), {}};
  ParameterStore store(tap.bus());
  store.boot();
  ParameterSet s = store.current();
  s.max_acceleration_um_s2 = 5000;  // so that writing 20000 is a change
  ASSERT_TRUE(store.save(s).ok());
  ASSERT_TRUE(store.save(defaults()).ok());  // A, then B: the next save writes copy A
  tap.frames.clear();
  const SaveResult r = store.set_parameter(id_of(ParamId::MaxAcceleration), 20000);
  ASSERT_EQ(r.status, StoreStatus::Ok);
  EXPECT_EQ(r.attempts, 1);
  ASSERT_EQ(tap.frames.size(), 5U);
  const auto& f = tap.frames;
  // 1. WREN + WRITE 0x004C: the spoil key, 4 bytes
  EXPECT_EQ(f[0], std::vector<std::uint8_t>{opcode::kWren});
  ASSERT_EQ(f[1].size(), 3U + 4U);
  EXPECT_EQ(f[1][0], opcode::kWrite);
  EXPECT_EQ(f[1][1], 0x00);
  EXPECT_EQ(f[1][2], 0x4C);
  // 2. WREN + WRITE 0x0000: the record, 20000 LSB first
  EXPECT_EQ(f[2], std::vector<std::uint8_t>{opcode::kWren});
  ASSERT_EQ(f[3].size(), 3U + kRecordSize);
  EXPECT_EQ(f[3][0], opcode::kWrite);
  EXPECT_EQ(f[3][1], 0x00);
  EXPECT_EQ(f[3][2], 0x00);
  EXPECT_EQ(f[3][3], 0x20);
  EXPECT_EQ(f[3][4], 0x4E);
  EXPECT_EQ(f[3][5], 0x00);
  EXPECT_EQ(f[3][6], 0x00);
  // the record's last 4 bytes are the CRC-32 of the 76 before them, and the key is its complement
  const std::uint32_t crc = crc32(std::span<const std::uint8_t>(f[3].data() + 3, 0x4C));
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(f[3][3 + 0x4C + i], static_cast<std::uint8_t>(crc >> (8 * i))) << i;
    EXPECT_EQ(f[1][3 + i], static_cast<std::uint8_t>(~crc >> (8 * i))) << i;
  }
  // 3. READ 0x0000 of the whole record
  ASSERT_EQ(f[4].size(), 3U + kRecordSize);
  EXPECT_EQ(f[4][0], opcode::kRead);
  EXPECT_EQ(f[4][1], 0x00);
  EXPECT_EQ(f[4][2], 0x00);
  EXPECT_EQ(chip->memory()[0x0000], 0x20);
  EXPECT_EQ(chip->memory()[0x0001], 0x4E);
}

TEST(storage_golden, first_save_on_a_blank_chip_puts_20000_at_0x0000) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  EXPECT_TRUE(store.boot().defaults_used());
  ASSERT_TRUE(store.set_parameter(id_of(ParamId::MaxAcceleration), 20000).ok());
  const auto m = chip->memory();
  EXPECT_EQ(m[0x0000], 0x20);
  EXPECT_EQ(m[0x0001], 0x4E);
  EXPECT_EQ(m[0x0002], 0x00);
  EXPECT_EQ(m[0x0003], 0x00);
}

TEST(storage_codec, signed_items_round_trip_in_twos_complement) {
  const ParameterSet s = variant_set();
  RecordBytes r{};
  encode_record(s, 77, r);
  EXPECT_EQ(r[entry(ParamId::StallGuardThreshold).offset], 0xF9);  // -7
  const DecodeResult d = decode_record(r);
  ASSERT_EQ(d.status, RecordStatus::Valid);
  EXPECT_EQ(d.set, s);
  EXPECT_EQ(d.sequence, 77U);
}

TEST(storage_codec, every_single_bit_flip_is_rejected) {
  RecordBytes r{};
  encode_record(variant_set(), 5, r);
  std::size_t rejected = 0;
  for (std::size_t i = 0; i < kRecordSize; ++i) {
    for (int b = 0; b < 8; ++b) {
      RecordBytes c = r;
      c[i] = static_cast<std::uint8_t>(c[i] ^ (1U << b));
      if (decode_record(c).status != RecordStatus::Valid) ++rejected;
    }
  }
  EXPECT_EQ(rejected, kRecordSize * 8);
}

TEST(storage_codec, wrapped_sequence_orders_correctly) {
  EXPECT_TRUE(sequence_newer(0, 0xFFFFFFFFU));
  EXPECT_FALSE(sequence_newer(0xFFFFFFFFU, 0));
  EXPECT_TRUE(sequence_newer(8, 7));
  EXPECT_FALSE(sequence_newer(7, 7));
}

TEST(storage_validate, defaults_are_valid_and_rules_bite) {
  EXPECT_TRUE(validate(defaults()).ok());
  ParameterSet s = defaults();
  s.microsteps = 3;
  EXPECT_EQ(validate(s).error, ValidationError::NotPowerOfTwo);
  s = defaults();
  s.run_current_cs = 32;
  EXPECT_EQ(validate(s).error, ValidationError::OutOfRange);
  EXPECT_EQ(validate(s).id, ParamId::RunCurrent);
  s = defaults();
  s.slow_speed_um_s = s.fast_speed_um_s + 1;
  EXPECT_EQ(validate(s).error, ValidationError::SpeedOrder);
  s = defaults();
  s.soft_min_y_um = s.soft_max_y_um;
  EXPECT_EQ(validate(s).error, ValidationError::LimitOrder);
}

// ---------------------------------------------------------------- the chip model

TEST(storage_model, write_needs_wren_and_the_latch_clears_after_write) {
  auto chip = std::make_unique<Mb85rs256b>();
  FramDevice dev(chip->bus());
  std::array<std::uint8_t, 5> raw{opcode::kWrite, 0x00, 0x10, 0xAA, 0xBB};
  std::array<std::uint8_t, 5> rx{};
  chip->transfer(raw, rx);
  EXPECT_EQ(chip->memory()[0x10], 0x00) << "WRITE without WREN must be ignored";
  std::array<std::uint8_t, 1> wren{opcode::kWren}, r1{};
  chip->transfer(wren, r1);
  EXPECT_EQ(dev.read_status().value() & status::kWel, status::kWel);
  chip->transfer(raw, rx);
  EXPECT_EQ(chip->memory()[0x10], 0xAA);
  EXPECT_EQ(chip->memory()[0x11], 0xBB);
  EXPECT_EQ(dev.read_status().value() & status::kWel, 0) << "WEL must clear at the end of WRITE";
  raw[3] = 0x11;
  chip->transfer(raw, rx);
  EXPECT_EQ(chip->memory()[0x10], 0xAA);
  chip->transfer(wren, r1);
  std::array<std::uint8_t, 1> wrdi{opcode::kWrdi};
  chip->transfer(wrdi, r1);
  chip->transfer(raw, rx);
  EXPECT_EQ(chip->memory()[0x10], 0xAA) << "WRDI must clear the latch";
}

TEST(storage_model, block_protection_follows_bp_bits) {
  auto chip = std::make_unique<Mb85rs256b>();
  FramDevice dev(chip->bus());
  const std::array<std::uint8_t, 1> v{0x5A};
  std::array<std::uint8_t, 1> got{};
  ASSERT_TRUE(dev.write_status(status::kBp0));  // upper quarter
  EXPECT_EQ(dev.read_status().value(), status::kBp0) << "WRSR clears WEL";
  dev.write(0x5FFF, v);
  dev.write(0x6000, v);
  EXPECT_EQ(chip->memory()[0x5FFF], 0x5A);
  EXPECT_EQ(chip->memory()[0x6000], 0x00);
  dev.write_status(status::kBp1);  // upper half
  dev.write(0x4000, v);
  dev.write(0x3FFF, v);
  EXPECT_EQ(chip->memory()[0x4000], 0x00);
  EXPECT_EQ(chip->memory()[0x3FFF], 0x5A);
  dev.write_status(status::kBp0 | status::kBp1);  // all
  dev.write(0x0000, v);
  EXPECT_EQ(chip->memory()[0x0000], 0x00);
  ASSERT_TRUE(dev.read(0x3FFF, got));
  EXPECT_EQ(got[0], 0x5A) << "reads are never blocked";
  // WRSR without WREN is ignored
  std::array<std::uint8_t, 2> wrsr{opcode::kWrsr, 0x00}, rx{};
  chip->transfer(wrsr, rx);
  EXPECT_EQ(dev.read_status().value(), status::kBp0 | status::kBp1);
  // WPEN with the WP pin low locks the status register
  dev.write_status(status::kWpen);
  chip->set_wp_pin(false);
  dev.write_status(status::kBp0);
  EXPECT_EQ(dev.read_status().value(), status::kWpen);
}

TEST(storage_model, address_rolls_over_at_the_top) {
  auto chip = std::make_unique<Mb85rs256b>();
  FramDevice dev(chip->bus());
  const std::array<std::uint8_t, 2> v{0x01, 0x02};
  dev.write(0x7FFF, v);
  EXPECT_EQ(chip->memory()[0x7FFF], 0x01);
  EXPECT_EQ(chip->memory()[0x0000], 0x02);
  dev.write(0xFFFF, v);  // A15 ignored
  EXPECT_EQ(chip->memory()[0x7FFF], 0x01);
}

TEST(storage_model, power_cut_keeps_exactly_the_completed_bytes) {
  auto chip = std::make_unique<Mb85rs256b>();
  std::array<std::uint8_t, 1> wren{opcode::kWren}, r1{};
  chip->transfer(wren, r1);
  std::array<std::uint8_t, 7> raw{opcode::kWrite, 0x00, 0x00, 1, 2, 3, 4}, rx{};
  chip->arm_power_cut_after(5);  // opcode, two address bytes, two data bytes
  chip->transfer(raw, rx);
  EXPECT_FALSE(chip->powered());
  EXPECT_EQ(chip->memory()[0], 1);
  EXPECT_EQ(chip->memory()[1], 2);
  EXPECT_EQ(chip->memory()[2], 0);
  chip->power_on();
  FramDevice dev(chip->bus());
  EXPECT_EQ(dev.read_status().value() & status::kWel, 0) << "power-up clears WEL";
}

// ---------------------------------------------------------------- the store

TEST(storage_store, blank_chip_boots_defaults_and_reports_it) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  const BootReport r = store.boot();
  EXPECT_TRUE(r.defaults_used());
  EXPECT_EQ(r.copy[0], RecordStatus::BadCrc);
  EXPECT_EQ(r.copy[1], RecordStatus::BadCrc);
  EXPECT_EQ(store.current(), defaults());
  EXPECT_EQ(chip->bytes_clocked(), 2 * (3 + kRecordSize)) << "boot only reads";
}

TEST(storage_store, saves_alternate_copies_and_boot_takes_the_newest) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  store.boot();
  ParameterSet a = variant_set();
  ASSERT_TRUE(store.save(a).ok());
  ParameterSet b = a;
  b.max_acceleration_um_s2 = 777;
  ASSERT_TRUE(store.save(b).ok());
  ParameterStore again(chip->bus());
  const BootReport r = again.boot();
  EXPECT_EQ(r.source, BootSource::CopyB);
  EXPECT_EQ(r.sequence, 2U);
  EXPECT_EQ(again.current(), b);
  EXPECT_EQ(decode_record(std::span<const std::uint8_t, kRecordSize>(chip->memory().data(), kRecordSize)).set, a);
}

TEST(storage_store, corrupt_newest_copy_falls_back_to_the_older) {
  auto chip = std::make_unique<Mb85rs256b>();
  write_record(*chip, 0, variant_set(), 10);
  write_record(*chip, 1, defaults(), 11);
  for (std::size_t i = 0; i < kRecordSize; ++i) {
    auto c = std::make_unique<Mb85rs256b>(*chip);
    c->memory()[kCopyBase[1] + i] ^= 0x10;
    ParameterStore store(c->bus());
    const BootReport r = store.boot();
    EXPECT_EQ(r.source, BootSource::CopyA) << "byte " << i;
    EXPECT_EQ(store.current(), variant_set());
  }
}

TEST(storage_store, out_of_range_value_invalidates_a_crc_valid_copy) {
  auto chip = std::make_unique<Mb85rs256b>();
  write_record(*chip, 0, variant_set(), 10);
  write_record(*chip, 1, defaults(), 11);
  chip->memory()[kCopyBase[1] + entry(ParamId::RunCurrent).offset] = 32;
  refresh_crc(*chip, 1);
  ParameterStore store(chip->bus());
  const BootReport r = store.boot();
  EXPECT_EQ(r.copy[1], RecordStatus::BadValue);
  EXPECT_EQ(r.source, BootSource::CopyA);
  // and the layout version is a value like any other
  chip->memory()[kCopyBase[0] + entry(ParamId::LayoutVersion).offset] = 2;
  refresh_crc(*chip, 0);
  ParameterStore none(chip->bus());
  EXPECT_TRUE(none.boot().defaults_used());
  EXPECT_EQ(none.current(), defaults());
}

TEST(storage_store, wrapped_sequence_boot_prefers_zero_over_max) {
  auto chip = std::make_unique<Mb85rs256b>();
  write_record(*chip, 0, variant_set(), 0xFFFFFFFFU);
  write_record(*chip, 1, defaults(), 0);
  ParameterStore store(chip->bus());
  EXPECT_EQ(store.boot().source, BootSource::CopyB);
  ASSERT_TRUE(store.save(variant_set()).ok());
  EXPECT_EQ(store.sequence(), 1U);
}

TEST(storage_store, refused_input_writes_nothing) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  store.boot();
  ASSERT_TRUE(store.save(variant_set()).ok());
  const auto before_bytes = chip->bytes_clocked();
  const std::vector<std::uint8_t> before_mem(chip->memory().begin(), chip->memory().end());
  for (const MapEntry& e : kItemMap) {
    const std::uint8_t id = id_of(e.id);
    const SaveResult lo = store.set_parameter(id, e.min - 1);
    const SaveResult hi = store.set_parameter(id, e.max + 1);
    const StoreStatus want = e.role == Role::User || e.role == Role::Factory ? StoreStatus::OutOfRange : StoreStatus::NotSettable;
    EXPECT_EQ(lo.status, want) << e.name;
    EXPECT_EQ(hi.status, want) << e.name;
    EXPECT_EQ(lo.attempts, 0);
  }
  EXPECT_EQ(store.set_parameter(kItemCount, 1).status, StoreStatus::UnknownId);
  EXPECT_EQ(store.set_parameter(255, 1).status, StoreStatus::UnknownId);
  EXPECT_EQ(store.set_parameter(id_of(ParamId::Microsteps), 12).status, StoreStatus::NotPowerOfTwo);
  EXPECT_EQ(store.set_parameter(id_of(ParamId::SlowSpeed), 999'999).status, StoreStatus::Inconsistent);
  EXPECT_EQ(store.set_parameter(id_of(ParamId::SoftMaxX), -1500).status, StoreStatus::Inconsistent);
  ParameterSet bad = variant_set();
  bad.hold_current_cs = 40;
  EXPECT_EQ(store.save(bad).status, StoreStatus::OutOfRange);
  EXPECT_EQ(store.save(bad).item, ParamId::HoldCurrent);
  EXPECT_EQ(chip->bytes_clocked(), before_bytes);
  EXPECT_TRUE(std::equal(before_mem.begin(), before_mem.end(), chip->memory().begin()));
  EXPECT_EQ(store.current(), variant_set());
}

TEST(storage_store, transient_write_error_is_retried_and_reported) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  store.boot();
  chip->flip_on_write(kCopyBase[0] + 5, 0x04, 1);
  const SaveResult r = store.save(variant_set());
  EXPECT_EQ(r.status, StoreStatus::Ok);
  EXPECT_EQ(r.attempts, 2);
  EXPECT_FALSE(store.storage_fault());
}

TEST(storage_store, persistent_write_error_raises_a_fault_and_keeps_the_old_set) {
  for (int kind = 0; kind < 3; ++kind) {
    auto chip = std::make_unique<Mb85rs256b>();
    ParameterStore store(chip->bus());
    store.boot();
    ASSERT_TRUE(store.save(variant_set()).ok());  // lands in A; the next save targets B
    const std::uint16_t a = static_cast<std::uint16_t>(kCopyBase[1] + 9);
    if (kind == 0) chip->stick_bits(a, 0x80, 0x80);
    if (kind == 1) chip->flip_on_write(a, 0x01, kMaxSaveAttempts);
    if (kind == 2) {
      FramDevice(chip->bus()).write_status(status::kBp0 | status::kBp1);
    }
    const SaveResult r = store.save(defaults());
    EXPECT_EQ(r.status, StoreStatus::StorageFault) << kind;
    EXPECT_EQ(r.attempts, kMaxSaveAttempts);
    EXPECT_TRUE(store.storage_fault());
    EXPECT_EQ(store.current(), variant_set());
    chip->clear_faults();
    ParameterStore again(chip->bus());
    again.boot();
    EXPECT_EQ(again.current(), variant_set()) << kind;
  }
}

// When only the read-back path fails, the chip holds the new record intact; it failed
// verification, so it must not win at the next boot.
TEST(storage_store, unverified_record_is_never_used_even_if_intact) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  store.boot();
  ASSERT_TRUE(store.save(variant_set()).ok());
  chip->flip_on_read(static_cast<std::uint16_t>(kCopyBase[1] + 2), 0x01, kMaxSaveAttempts);
  EXPECT_EQ(store.save(defaults()).status, StoreStatus::StorageFault);
  ParameterStore again(chip->bus());
  const BootReport r = again.boot();
  EXPECT_EQ(r.source, BootSource::CopyA);
  EXPECT_EQ(again.current(), variant_set());
}

TEST(storage_store, fault_clears_after_a_verified_save) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  store.boot();
  chip->stick_bits(kCopyBase[0], 0x01, 0x01);
  ParameterSet s = defaults();
  s.max_acceleration_um_s2 = 20000;  // 0x20: bit 0 clear, so the stuck bit shows
  EXPECT_EQ(store.save(s).status, StoreStatus::StorageFault);
  chip->clear_faults();
  EXPECT_TRUE(store.save(s).ok());
  EXPECT_FALSE(store.storage_fault());
}

TEST(storage_step_counter, valid_only_after_orderly_shutdown_and_cleared_before_motion) {
  auto chip = std::make_unique<Mb85rs256b>();
  {
    ParameterStore store(chip->bus());
    store.boot();
    EXPECT_FALSE(store.current().step_counts_valid);
    ASSERT_TRUE(store.record_shutdown(123456, -42).ok());
  }
  {
    ParameterStore store(chip->bus());
    store.boot();
    EXPECT_TRUE(store.current().step_counts_valid);
    EXPECT_EQ(store.current().step_count_x, 123456);
    EXPECT_EQ(store.current().step_count_y, -42);
    const SaveResult r = store.begin_motion();
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.attempts, 1);
    const auto bytes = chip->bytes_clocked();
    EXPECT_EQ(store.begin_motion().attempts, 0) << "already clear: no write";
    EXPECT_EQ(chip->bytes_clocked(), bytes);
  }
  {
    // a cut right after motion started (no orderly shutdown) must not revive the counters
    ParameterStore store(chip->bus());
    store.boot();
    EXPECT_FALSE(store.current().step_counts_valid);
  }
}
