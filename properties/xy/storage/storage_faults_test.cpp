// Storage under SPI bus errors (the HAL reporting a failed transaction, as opposed to the
// model's silent faults): FramDevice refuses oversize transfers without traffic and reports
// every failed transaction; ParameterStore boots on defaults from an unreadable chip, and a
// save whose write or read-back keeps failing is a StorageFault that leaves the current set,
// and what the next boot loads, unchanged. Plus the address-map checks on bad maps and the
// typed rejections of invalid sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/xy/storage/fram_device.hpp"
#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"

namespace {

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;

// The FRAM model behind a bus that can report errors: every transaction whose opcode is in
// `failing` fails, and so does transaction number `fail_at` (0-based). A failed transaction
// never reaches the chip.
struct FlakyBus {
  Mb85rs256b chip;
  std::vector<std::uint8_t> failing;
  std::optional<std::size_t> fail_at;
  std::size_t transactions = 0;
  std::vector<std::uint8_t> opcodes;   // of the transactions that reached the chip

  static bool transfer(void* context, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
    auto* self = static_cast<FlakyBus*>(context);
    const std::size_t n = self->transactions++;
    if (self->fail_at && n == *self->fail_at) return false;
    for (const std::uint8_t op : self->failing) {
      if (!tx.empty() && tx[0] == op) return false;
    }
    self->opcodes.push_back(tx.empty() ? 0 : tx[0]);
    return self->chip.transfer(tx, rx);
  }
  SpiBus bus() noexcept { return SpiBus{&FlakyBus::transfer, this}; }
};

ParameterSet other_set() {
  ParameterSet s = defaults();
  s.max_acceleration_um_s2 += 1000;
  s.run_current_cs = 12;
  return s;
}

}  // namespace

TEST(storage_faults, oversize_transfers_are_refused_without_traffic) {
  FlakyBus b;
  const FramDevice fram(b.bus());
  std::array<std::uint8_t, kMaxTransfer + 1> big{};
  EXPECT_FALSE(fram.read(0, big));
  EXPECT_FALSE(fram.write(0, big));
  EXPECT_EQ(b.transactions, 0u);
  std::array<std::uint8_t, kMaxTransfer> fits{};
  fits.fill(0x5A);
  EXPECT_TRUE(fram.write(0, fits));
  std::array<std::uint8_t, kMaxTransfer> back{};
  EXPECT_TRUE(fram.read(0, back));
  EXPECT_EQ(back, fits);
}

TEST(storage_faults, every_failed_transaction_is_reported) {
  {  // READ fails: false, the caller's buffer untouched
    FlakyBus b;
    b.chip.memory()[0x10] = 0x42;
    b.failing = {opcode::kRead};
    const FramDevice fram(b.bus());
    std::array<std::uint8_t, 1> data{0x99};
    EXPECT_FALSE(fram.read(0x10, data));
    EXPECT_EQ(data[0], 0x99);
  }
  {  // WREN fails: no WRITE is sent at all
    FlakyBus b;
    b.failing = {opcode::kWren};
    const FramDevice fram(b.bus());
    const std::array<std::uint8_t, 2> data{1, 2};
    EXPECT_FALSE(fram.write(0x20, data));
    EXPECT_TRUE(b.opcodes.empty());
    EXPECT_EQ(b.chip.memory()[0x20], 0);
    EXPECT_FALSE(fram.write_status(status::kBp0 | status::kBp1));
    EXPECT_TRUE(b.opcodes.empty());
    EXPECT_EQ(b.chip.status() & (status::kBp0 | status::kBp1), 0);
  }
  {  // WRITE / WRSR themselves fail after a good WREN
    FlakyBus b;
    b.failing = {opcode::kWrite, opcode::kWrsr};
    const FramDevice fram(b.bus());
    const std::array<std::uint8_t, 2> data{1, 2};
    EXPECT_FALSE(fram.write(0x20, data));
    EXPECT_FALSE(fram.write_status(status::kBp0));
    EXPECT_EQ(b.opcodes, (std::vector<std::uint8_t>{opcode::kWren, opcode::kWren}));
    EXPECT_EQ(b.chip.memory()[0x20], 0);
  }
  {  // RDSR fails: no status
    FlakyBus b;
    b.failing = {opcode::kRdsr};
    const FramDevice fram(b.bus());
    EXPECT_EQ(fram.read_status(), std::nullopt);
  }
  {  // healthy: the status register round-trips
    FlakyBus b;
    const FramDevice fram(b.bus());
    ASSERT_TRUE(fram.write_status(status::kBp0));
    const auto st = fram.read_status();
    ASSERT_TRUE(st.has_value());
    EXPECT_EQ(*st & (status::kBp0 | status::kBp1), status::kBp0);
  }
}

TEST(storage_faults, boot_from_an_unreadable_chip_uses_the_defaults) {
  FlakyBus b;
  {
    ParameterStore writer(b.bus());
    (void)writer.boot();
    ASSERT_TRUE(writer.save(other_set()).ok());
  }
  b.failing = {opcode::kRead};
  ParameterStore store(b.bus());
  const BootReport r = store.boot();
  EXPECT_EQ(r.source, BootSource::Defaults);
  EXPECT_TRUE(r.defaults_used());
  EXPECT_EQ(r.copy[0], RecordStatus::Unreadable);
  EXPECT_EQ(r.copy[1], RecordStatus::Unreadable);
  EXPECT_EQ(r.sequence, 0u);
  EXPECT_TRUE(store.current() == defaults());
}

// The write keeps failing, or the write goes out but the read-back keeps failing: after
// kMaxSaveAttempts rounds the save is a StorageFault, the current set is unchanged, and the
// next boot (bus healthy again) still loads the previous set: an unverified copy never wins.
TEST(storage_faults, save_that_cannot_be_verified_is_a_fault_and_changes_nothing) {
  for (const std::uint8_t dead : {opcode::kWrite, opcode::kRead, opcode::kWren}) {
    SCOPED_TRACE(testing::Message() << "failing opcode 0x" << std::hex << int{dead});
    FlakyBus b;
    ParameterStore store(b.bus());
    (void)store.boot();
    const ParameterSet first = defaults();
    ASSERT_TRUE(store.save(first).ok());
    const std::uint32_t seq = store.sequence();

    b.failing = {dead};
    const SaveResult r = store.save(other_set());
    EXPECT_EQ(r.status, StoreStatus::StorageFault);
    EXPECT_EQ(r.attempts, kMaxSaveAttempts);
    EXPECT_TRUE(store.storage_fault());
    EXPECT_TRUE(store.current() == first);
    EXPECT_EQ(store.sequence(), seq);

    b.failing.clear();
    ParameterStore again(b.bus());
    const BootReport boot = again.boot();
    EXPECT_FALSE(boot.defaults_used());
    EXPECT_EQ(boot.sequence, seq);
    EXPECT_TRUE(again.current() == first);

    // The fault is latched until the next verified save clears it.
    ASSERT_TRUE(store.save(other_set()).ok());
    EXPECT_FALSE(store.storage_fault());
  }
}

// An attempt is five transactions (docs/storage.md, "Save protocol"): WREN, WRITE of the spoil
// key, WREN, WRITE of the record, READ. Any one of them failing costs exactly one more attempt.
TEST(storage_faults, one_failed_transaction_costs_one_more_attempt) {
  for (std::size_t n = 0; n < 5; ++n) {
    SCOPED_TRACE(testing::Message() << "failing transaction " << n << " of the first attempt");
    FlakyBus b;
    ParameterStore store(b.bus());
    (void)store.boot();
    b.transactions = 0;
    b.fail_at = n;
    const SaveResult r = store.save(other_set());
    EXPECT_EQ(r.status, StoreStatus::Ok);
    EXPECT_EQ(r.attempts, 2u);
    EXPECT_EQ(b.transactions, (n + 1) + 5u) << "a failed transaction ends its attempt; the next attempt is whole";
    EXPECT_TRUE(store.current() == other_set());
  }
}

TEST(storage_faults, invalid_sets_are_typed_rejections_that_write_nothing) {
  FlakyBus b;
  ParameterStore store(b.bus());
  (void)store.boot();
  const std::size_t before = b.transactions;

  ParameterSet s = defaults();
  s.microsteps = 3;
  SaveResult r = store.save(s);
  EXPECT_EQ(r.status, StoreStatus::NotPowerOfTwo);
  EXPECT_EQ(r.item, ParamId::Microsteps);
  EXPECT_EQ(r.attempts, 0u);

  s = defaults();
  s.soft_min_y_um = s.soft_max_y_um;
  r = store.save(s);
  EXPECT_EQ(r.status, StoreStatus::Inconsistent);
  EXPECT_EQ(r.item, ParamId::SoftMinY);

  r = store.set_parameter(static_cast<std::uint8_t>(ParamId::Microsteps), 12);
  EXPECT_EQ(r.status, StoreStatus::NotPowerOfTwo);
  EXPECT_EQ(r.item, ParamId::Microsteps);

  EXPECT_EQ(b.transactions, before);
  EXPECT_TRUE(store.current() == defaults());
}

TEST(storage_faults, set_field_refuses_meta_items) {
  for (const ParamId meta : {ParamId::LayoutVersion, ParamId::Sequence, ParamId::Crc}) {
    ParameterSet s = defaults();
    EXPECT_FALSE(set_field(s, meta, 1));
    EXPECT_TRUE(s == defaults());
    EXPECT_EQ(get_field(s, meta), std::nullopt);
  }
}

TEST(storage_faults, map_checks_reject_overlapping_empty_and_oversize_regions) {
  const std::array<Region, 2> disjoint{Region{ParamId::FastSpeed, 0, 0, 4}, Region{ParamId::SlowSpeed, 0, 4, 4}};
  const std::array<Region, 2> overlap{Region{ParamId::FastSpeed, 0, 0, 4}, Region{ParamId::SlowSpeed, 0, 3, 4}};
  const std::array<Region, 2> inside{Region{ParamId::FastSpeed, 0, 8, 1}, Region{ParamId::SlowSpeed, 0, 4, 8}};
  const std::array<Region, 2> reversed{Region{ParamId::FastSpeed, 0, 4, 4}, Region{ParamId::SlowSpeed, 0, 0, 4}};
  EXPECT_TRUE(regions_disjoint(disjoint));
  EXPECT_TRUE(regions_disjoint(reversed));
  EXPECT_FALSE(regions_disjoint(overlap));
  EXPECT_FALSE(regions_disjoint(inside));

  EXPECT_TRUE(regions_fit_chip(disjoint));
  const std::array<Region, 1> empty{Region{ParamId::FastSpeed, 0, 0, 0}};
  const std::array<Region, 1> last_byte{Region{ParamId::FastSpeed, 0, kChip.size_bytes - 1, 1}};
  const std::array<Region, 1> past_end{Region{ParamId::FastSpeed, 0, kChip.size_bytes - 1, 2}};
  EXPECT_FALSE(regions_fit_chip(empty));
  EXPECT_TRUE(regions_fit_chip(last_byte));
  EXPECT_FALSE(regions_fit_chip(past_end));
  // ... and the real map passes both.
  EXPECT_TRUE(regions_disjoint(address_map()));
  EXPECT_TRUE(regions_fit_chip(address_map()));
}

// A copy whose CRC is intact but whose set breaks a cross rule (written by a buggy or older
// firmware) is BadValue naming the item, and boot does not load it.
TEST(storage_faults, intact_record_breaking_a_cross_rule_is_not_loaded) {
  ParameterSet s = defaults();
  s.soft_min_x_um = s.soft_max_x_um;
  ASSERT_FALSE(validate(s).ok());
  RecordBytes image{};
  encode_record(s, 5, image);
  const DecodeResult d = decode_record(image);
  EXPECT_EQ(d.status, RecordStatus::BadValue);
  EXPECT_EQ(d.bad_item, ParamId::SoftMinX);

  FlakyBus b;
  std::copy(image.begin(), image.end(), b.chip.memory().begin() + kCopyBase[0]);
  ParameterStore store(b.bus());
  const BootReport r = store.boot();
  EXPECT_EQ(r.copy[0], RecordStatus::BadValue);
  EXPECT_TRUE(r.defaults_used());
  EXPECT_TRUE(store.current() == defaults());
}
