// Deterministic, seeded fuzzing of boot in every preset (the libFuzzer target fram_image
// does the same coverage-guided in the fuzz preset): images built from valid records, then
// torn, bit-flipped, re-CRC'd or replaced by noise. Boot must end with the newest copy that
// an independent checker accepts, byte-identical to the chip, or with the reported defaults.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <memory>

#include "core/xy/storage/crc32.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"
#include "storage_test_support.hpp"

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;

namespace {

// Bitwise CRC-32, written apart from the table-driven one under test.
std::uint32_t reference_crc(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFU;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320U & (0U - (c & 1U)));
  }
  return ~c;
}

std::uint32_t le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

}  // namespace

RC_GTEST_PROP(storage_fuzz, boot_from_any_image_ends_valid_or_with_defaults, ()) {
  auto chip = std::make_unique<Mb85rs256b>();
  std::uint8_t* m = chip->memory().data();
  for (std::size_t c = 0; c < kCopyCount; ++c) {
    std::uint8_t* rec = m + kCopyBase[c];
    switch (test::pick(4)) {
      case 0: break;  // blank
      case 1:
        for (std::size_t i = 0; i < kRecordSize; ++i) rec[i] = *rc::gen::arbitrary<std::uint8_t>();
        break;
      default: {
        RecordBytes r{};
        encode_record(test::gen_valid_set(), *rc::gen::arbitrary<std::uint32_t>(), r);
        std::copy(r.begin(), r.end(), rec);
      }
    }
    const int edits = test::pick(3) == 0 ? 1 + test::pick(3) : 0;
    for (int e = 0; e < edits; ++e) {
      const auto at = static_cast<std::size_t>(test::pick(static_cast<int>(kRecordSize)));
      rec[at] = *rc::gen::arbitrary<std::uint8_t>();
    }
    if (*rc::gen::arbitrary<bool>()) {
      const std::uint32_t crc = reference_crc(rec, kCrcOffset);
      for (int b = 0; b < 4; ++b) rec[kCrcOffset + static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(crc >> (8 * b));
    }
  }

  // Independent acceptance: CRC by the reference, then the decoder's range verdict.
  std::array<bool, kCopyCount> ok{};
  std::array<std::uint32_t, kCopyCount> seq{};
  for (std::size_t c = 0; c < kCopyCount; ++c) {
    const std::uint8_t* rec = m + kCopyBase[c];
    const bool crc_ok = reference_crc(rec, kCrcOffset) == le32(rec + kCrcOffset);
    const DecodeResult d = decode_record(std::span<const std::uint8_t, kRecordSize>(rec, kRecordSize));
    RC_ASSERT(crc_ok == (d.status != RecordStatus::BadCrc));
    ok[c] = d.status == RecordStatus::Valid;
    seq[c] = le32(rec + entry(ParamId::Sequence).offset);
    RC_TAG(d.status == RecordStatus::Valid ? "valid" : d.status == RecordStatus::BadValue ? "bad value" : "bad crc");
  }

  ParameterStore store(chip->bus());
  const BootReport rep = store.boot();
  if (!ok[0] && !ok[1]) {
    RC_ASSERT(rep.defaults_used());
    RC_ASSERT(store.current() == defaults());
    return;
  }
  RC_ASSERT(!rep.defaults_used());
  const std::size_t c = rep.source == BootSource::CopyA ? 0 : 1;
  RC_ASSERT(ok[c]);
  RC_ASSERT(!ok[1 - c] || !sequence_newer(seq[1 - c], seq[c]));
  RC_ASSERT(validate(store.current()).ok());
  RecordBytes again{};
  encode_record(store.current(), rep.sequence, again);
  RC_ASSERT(std::equal(again.begin(), again.end(), m + kCopyBase[c]));
}
