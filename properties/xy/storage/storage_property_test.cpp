// Properties of the storage module: power-cut safety at every byte of a save, codec
// round trips, and the set-by-id contract (accepted iff valid; refused writes nothing).
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "core/xy/storage/crc32.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"
#include "storage_test_support.hpp"

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;
using ap::xy_storage::test::gen_valid_set;

namespace {

ParameterSet boot_set(Mb85rs256b& chip) {
  ParameterStore s(chip.bus());
  s.boot();
  return s.current();
}

std::uint32_t boot_sequence(Mb85rs256b& chip) {
  ParameterStore s(chip.bus());
  return s.boot().sequence;
}

// The save protocol's byte counts (docs/storage.md, "Save protocol"): the spoil (WREN, then
// WRITE opcode, two address bytes and the 4-byte key), the record (WREN, WRITE opcode, two
// address bytes, 80 bytes), the read-back (READ opcode, two address bytes, 80 bytes).
constexpr std::size_t kSpoilBytes = 1 + 3 + 4;
constexpr std::size_t kRecordWriteBytes = 1 + 3 + kRecordSize;
constexpr std::size_t kReadBackBytes = 3 + kRecordSize;
// The commit point: the copy is valid from the last CRC byte of the record write on, and not
// before (the spoil key differs from the new CRC in every byte).
constexpr std::size_t kCommitPoint = kSpoilBytes + kRecordWriteBytes;
constexpr std::size_t kSaveBytes = kSpoilBytes + kRecordWriteBytes + kReadBackBytes;

}  // namespace

// docs/storage.md: for random sets and every cut point k of a save, the next boot loads exactly the
// old set or exactly the new one; and which one is fixed by k: new iff k >= kCommitPoint
// (the protocol's commit point, whatever the target copy held before).
TEST(storage_power_cut, every_cut_point_of_a_save_gives_old_or_new) {
  std::size_t cut_points = 0;
  std::size_t cases = 0;
  const bool ok = rc::check("every cut point k of a save -> exactly old or exactly new", [&] {
    auto chip = std::make_unique<Mb85rs256b>();
    if (*rc::gen::arbitrary<bool>()) {
      // background the copies start from: anything, not only zeros
      const auto junk = *rc::gen::container<std::vector<std::uint8_t>>(0x200, rc::gen::arbitrary<std::uint8_t>());
      std::copy(junk.begin(), junk.end(), chip->memory().begin());
    }
    {
      ParameterStore setup(chip->bus());
      setup.boot();
      const int prior = ap::xy_storage::test::pick(4);  // varies which copy is active and what is stale
      for (int i = 0; i < prior; ++i) RC_ASSERT(setup.save(gen_valid_set()).ok());
    }
    const ParameterSet old_set = boot_set(*chip);
    const std::uint32_t old_seq = boot_sequence(*chip);
    const ParameterSet new_set = *rc::gen::oneOf(rc::gen::exec(gen_valid_set), rc::gen::just(old_set));

    // measure the save once, uncut: one attempt, kSaveBytes
    std::size_t save_bytes = 0;
    {
      auto probe = std::make_unique<Mb85rs256b>(*chip);
      ParameterStore s(probe->bus());
      s.boot();
      const std::size_t before = probe->bytes_clocked();
      const SaveResult r = s.save(new_set);
      RC_ASSERT(r.ok());
      RC_ASSERT(r.attempts == 1);
      save_bytes = probe->bytes_clocked() - before;
    }
    RC_ASSERT(save_bytes == kSaveBytes);
    const std::size_t commit = kCommitPoint;

    for (std::size_t k = 0; k <= save_bytes; ++k) {
      auto c = std::make_unique<Mb85rs256b>(*chip);
      {
        ParameterStore s(c->bus());
        s.boot();
        c->arm_power_cut_after(k);
        const SaveResult r = s.save(new_set);
        // A dead chip reads 0xFF, so a cut inside the read-back can still compare equal when
        // the unread tail is 0xFF; that save did complete its record, so only that is checked.
        if (k == save_bytes) RC_ASSERT(r.ok());
        if (r.ok()) RC_ASSERT(k >= commit);
      }
      c->power_on();
      const ParameterSet loaded = boot_set(*c);
      RC_LOG() << "k=" << k << " of " << save_bytes << " loaded old=" << (loaded == old_set)
               << " new=" << (loaded == new_set) << " old==new=" << (old_set == new_set) << "\n";
      RC_ASSERT(loaded == old_set || loaded == new_set);
      RC_ASSERT(loaded == (k >= commit ? new_set : old_set));
      // the copy, not only the set (old and new may be equal): the new record from the commit point on
      RC_ASSERT(boot_sequence(*c) == (k >= commit ? old_seq + 1U : old_seq));
      ++cut_points;
    }
    ++cases;
  });
  std::printf("storage_power_cut: tried %zu cut points over %zu random save pairs\n", cut_points, cases);
  EXPECT_TRUE(ok);
}

RC_GTEST_PROP(storage_codec, encode_decode_round_trip, ()) {
  const ParameterSet s = gen_valid_set();
  const auto seq = *rc::gen::arbitrary<std::uint32_t>();
  RecordBytes r{};
  encode_record(s, seq, r);
  const DecodeResult d = decode_record(r);
  RC_ASSERT(d.status == RecordStatus::Valid);
  RC_ASSERT(d.set == s);
  RC_ASSERT(d.sequence == seq);
}

// Any CRC-valid image decodes to a valid set whose re-encoding is byte-identical, or is
// refused as BadValue: the decoder never accepts what it could not have written.
RC_GTEST_PROP(storage_codec, decode_accepts_only_canonical_valid_records, ()) {
  RecordBytes r{};
  if (*rc::gen::arbitrary<bool>()) {
    encode_record(gen_valid_set(), *rc::gen::arbitrary<std::uint32_t>(), r);
    const auto i = static_cast<std::size_t>(ap::xy_storage::test::pick(static_cast<int>(kCrcOffset)));
    r[i] = *rc::gen::arbitrary<std::uint8_t>();
  } else {
    for (auto& b : r) b = *rc::gen::arbitrary<std::uint8_t>();
  }
  put_le(r, kCrcOffset, 4, crc32(std::span<const std::uint8_t>(r.data(), kCrcOffset)));
  const DecodeResult d = decode_record(r);
  RC_ASSERT(d.status != RecordStatus::BadCrc);
  RC_TAG(d.status == RecordStatus::Valid ? "valid" : "bad value");
  if (d.status == RecordStatus::Valid) {
    RC_ASSERT(validate(d.set).ok());
    RecordBytes again{};
    encode_record(d.set, d.sequence, again);
    RC_ASSERT(again == r);
  }
}

// set_parameter succeeds iff the value is in range and the resulting set is valid; a
// refusal clocks no SPI byte and leaves both the chip and the current set untouched.
RC_GTEST_PROP(storage_store, set_parameter_accepts_exactly_the_valid_values, ()) {
  auto chip = std::make_unique<Mb85rs256b>();
  ParameterStore store(chip->bus());
  store.boot();
  const ParameterSet start = gen_valid_set();
  RC_ASSERT(store.save(start).ok());
  const int id = ap::xy_storage::test::pick(static_cast<int>(kItemCount) + 2);
  std::int64_t value = 0;
  if (id < static_cast<int>(kItemCount)) {
    const MapEntry& e = kItemMap[static_cast<std::size_t>(id)];
    using ap::xy_storage::test::uniform;
    switch (ap::xy_storage::test::pick(3)) {
      case 0: value = uniform(e.min - 3, e.min + 3); break;  // around each bound
      case 1: value = uniform(e.max - 3, e.max + 3); break;
      default: value = uniform(e.min, e.max); break;
    }
  } else {
    value = *rc::gen::arbitrary<std::int32_t>();
  }
  const std::vector<std::uint8_t> before(chip->memory().begin(), chip->memory().end());
  const std::size_t clocked = chip->bytes_clocked();

  bool expect_ok = false;
  ParameterSet expected = start;
  if (id < static_cast<int>(kItemCount)) {
    const auto pid = static_cast<ParamId>(id);
    expect_ok = (entry(pid).role == Role::User || entry(pid).role == Role::Factory) && set_field(expected, pid, value) &&
                validate(expected).ok();
  }
  const SaveResult r = store.set_parameter(static_cast<std::uint8_t>(id), value);
  RC_ASSERT(r.ok() == expect_ok);
  RC_TAG(expect_ok ? "accepted" : "refused");
  if (expect_ok) {
    RC_ASSERT(store.current() == expected);
    RC_ASSERT(boot_set(*chip) == expected);
  } else {
    RC_ASSERT(r.attempts == 0);
    RC_ASSERT(chip->bytes_clocked() == clocked);
    RC_ASSERT(std::equal(before.begin(), before.end(), chip->memory().begin()));
    RC_ASSERT(store.current() == start);
  }
}
