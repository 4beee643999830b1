// Boots the parameter store from an arbitrary FRAM image. Never crashes; always ends with a
// valid set (the newest valid copy, byte-identical to what is stored) or the defaults with
// the report saying so; and a save afterwards verifies and survives a reboot.
//
// Input: byte 0 = flags (bit 0 / bit 1: recompute copy A's / copy B's CRC before booting, so
// the fuzzer also reaches the range and cross-rule checks behind the CRC); the rest is the
// image from address 0x0000.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "core/xy/storage/crc32.hpp"
#include "core/xy/storage/record.hpp"
#include "core/xy/storage/store.hpp"
#include "models/xy/fram/mb85rs256b.hpp"

using namespace ap::xy_storage;
using ap::model::Mb85rs256b;

namespace {

void check(bool cond) {
  if (!cond) std::abort();
}

std::span<std::uint8_t, kRecordSize> copy_bytes(Mb85rs256b& chip, std::size_t c) {
  return std::span<std::uint8_t, kRecordSize>(chip.memory().data() + kCopyBase[c], kRecordSize);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Mb85rs256b* chip = new Mb85rs256b();
  static std::size_t dirty = Mb85rs256b::kSize;  // bytes a previous run may have changed
  std::memset(chip->memory().data(), 0, dirty);
  chip->power_on();
  if (size == 0) return 0;
  const std::uint8_t flags = data[0];
  const std::size_t n = std::min(size - 1, Mb85rs256b::kSize);
  dirty = std::max<std::size_t>(n, kCopyBase[kCopyCount - 1] + kRecordSize);
  if (n > 0) std::memcpy(chip->memory().data(), data + 1, n);
  for (std::size_t c = 0; c < kCopyCount; ++c) {
    if ((flags & (1U << c)) != 0) {
      auto r = copy_bytes(*chip, c);
      put_le(r, kCrcOffset, 4, crc32(r.first(kCrcOffset)));
    }
  }

  // Independent expectation from the decoder alone.
  std::array<DecodeResult, kCopyCount> d{};
  for (std::size_t c = 0; c < kCopyCount; ++c) d[c] = decode_record(copy_bytes(*chip, c));

  ParameterStore store(chip->bus());
  const BootReport rep = store.boot();
  if (rep.defaults_used()) {
    check(store.current() == defaults());
    for (const auto& x : d) check(x.status != RecordStatus::Valid);
  } else {
    const std::size_t c = rep.source == BootSource::CopyA ? 0 : 1;
    const std::size_t o = 1 - c;
    check(d[c].status == RecordStatus::Valid);
    check(validate(store.current()).ok());
    check(store.current() == d[c].set);
    check(d[o].status != RecordStatus::Valid || !sequence_newer(d[o].sequence, d[c].sequence));
    RecordBytes again{};
    encode_record(store.current(), rep.sequence, again);
    check(std::equal(again.begin(), again.end(), copy_bytes(*chip, c).begin()));
  }

  ParameterSet next = store.current();
  next.step_counts_valid = !next.step_counts_valid;
  check(store.save(next).ok());
  ParameterStore after(chip->bus());
  after.boot();
  check(after.current() == next);
  return 0;
}
