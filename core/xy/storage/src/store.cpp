#include "core/xy/storage/store.hpp"

#include <algorithm>

namespace ap::xy_storage {

ParameterStore::ParameterStore(SpiBus bus) noexcept : fram_(bus), current_(defaults()) {}

void ParameterStore::read_copy(std::size_t copy, RecordBytes& buf, DecodeResult& out) const noexcept {
  if (!fram_.read(kCopyBase[copy], buf)) {
    out = DecodeResult{RecordStatus::Unreadable, ParamId::Crc, ParameterSet{}, 0};
    return;
  }
  out = decode_record(buf);
}

BootReport ParameterStore::boot() noexcept {
  std::array<DecodeResult, kCopyCount> copies{};
  RecordBytes buf{};
  for (std::size_t c = 0; c < kCopyCount; ++c) read_copy(c, buf, copies[c]);

  BootReport report{BootSource::Defaults, {copies[0].status, copies[1].status}, 0};
  std::size_t best = kCopyCount;
  for (std::size_t c = 0; c < kCopyCount; ++c) {
    if (copies[c].status != RecordStatus::Valid) continue;
    // Equal sequences cannot come from our own saves; prefer A so the choice is deterministic.
    if (best == kCopyCount || sequence_newer(copies[c].sequence, copies[best].sequence)) best = c;
  }
  fault_ = false;
  if (best == kCopyCount) {
    current_ = defaults();
    sequence_ = 0;
    active_ = kNoCopy;
    return report;
  }
  current_ = copies[best].set;
  sequence_ = copies[best].sequence;
  active_ = static_cast<std::uint8_t>(best);
  report.source = best == 0 ? BootSource::CopyA : BootSource::CopyB;
  report.sequence = sequence_;
  return report;
}

SaveResult ParameterStore::save(const ParameterSet& next) noexcept {
  const Validation v = validate(next);
  switch (v.error) {
    case ValidationError::None: break;
    case ValidationError::OutOfRange: return {StoreStatus::OutOfRange, 0, v.id};
    case ValidationError::NotPowerOfTwo: return {StoreStatus::NotPowerOfTwo, 0, v.id};
    case ValidationError::SpeedOrder:
    case ValidationError::LimitOrder: return {StoreStatus::Inconsistent, 0, v.id};
  }

  // Never the copy holding the current set: that copy is what a torn write falls back to.
  const std::size_t target = active_ == 0 ? 1U : 0U;
  const auto base = static_cast<std::uint16_t>(kCopyBase[target]);
  const auto crc_field = static_cast<std::uint16_t>(kCopyBase[target] + kCrcOffset);
  // The sequence may equal one a failed save left in the target copy: harmless, because no
  // byte of the target is written before its CRC field is keyed to this record (below).
  const std::uint32_t seq = sequence_ + 1U;
  RecordBytes image{};
  encode_record(next, seq, image);
  // The spoil key: the complement of this record's CRC. It differs from the CRC in all 32 bits,
  // and it depends only on this record, so spoiling twice changes nothing (docs/storage.md,
  // "Save protocol": a key taken from the stored CRC would undo an earlier spoil).
  std::array<std::uint8_t, 4> spoil{};
  put_le(spoil, 0, 4, ~get_le(image, kCrcOffset, 4));
  RecordBytes readback{};

  for (std::uint8_t attempt = 1; attempt <= kMaxSaveAttempts; ++attempt) {
    // 1. Spoil: the target's CRC field := key, before any record byte changes. Whatever the
    //    copy held (a failed save's record, an older set, noise), from here until the last
    //    CRC byte of step 2 lands it is new prefix + anything + key: never valid (except a
    //    2^-32 CRC collision), so a torn write cannot rebuild an old record from our prefix.
    // 2. The whole record in one WRITE; its CRC is its last field, so the copy becomes valid
    //    exactly when the last CRC byte lands (the commit point).
    // 3. Read back all 80 bytes and compare.
    const bool spoiled = fram_.write(crc_field, spoil);
    const bool written = spoiled && fram_.write(base, image);
    const bool read = written && fram_.read(base, readback);
    if (read && std::equal(image.begin(), image.end(), readback.begin())) {
      current_ = next;
      sequence_ = seq;
      active_ = static_cast<std::uint8_t>(target);
      fault_ = false;
      return {StoreStatus::Ok, attempt, ParamId::MaxAcceleration};
    }
  }

  // The copy may still hold our record intact if only the read path failed; spoil it again so
  // unverified data can never be picked at the next boot (best effort: the bus may be dead).
  (void)fram_.write(crc_field, spoil);
  fault_ = true;
  return {StoreStatus::StorageFault, kMaxSaveAttempts, ParamId::MaxAcceleration};
}

SaveResult ParameterStore::set_parameter(std::uint8_t id, std::int64_t value) noexcept {
  if (id >= kItemCount) return {StoreStatus::UnknownId, 0, ParamId::Crc};
  const ParamId pid = static_cast<ParamId>(id);
  if (entry(pid).role != Role::User && entry(pid).role != Role::Factory) return {StoreStatus::NotSettable, 0, pid};
  switch (check_item(pid, value)) {
    case ValidationError::None: break;
    case ValidationError::NotPowerOfTwo: return {StoreStatus::NotPowerOfTwo, 0, pid};
    case ValidationError::OutOfRange:
    case ValidationError::SpeedOrder:
    case ValidationError::LimitOrder: return {StoreStatus::OutOfRange, 0, pid};
  }
  ParameterSet next = current_;
  (void)set_field(next, pid, value);
  return save(next);
}

SaveResult ParameterStore::begin_motion() noexcept {
  if (!current_.step_counts_valid) return {StoreStatus::Ok, 0, ParamId::StepCountValid};
  ParameterSet next = current_;
  next.step_counts_valid = false;
  return save(next);
}

SaveResult ParameterStore::record_shutdown(std::int32_t step_count_x, std::int32_t step_count_y) noexcept {
  ParameterSet next = current_;
  next.step_count_x = step_count_x;
  next.step_count_y = step_count_y;
  next.step_counts_valid = true;
  return save(next);
}

}  // namespace ap::xy_storage
