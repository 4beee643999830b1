#include "core/xy/storage/record.hpp"

#include "core/xy/storage/crc32.hpp"

namespace ap::xy_storage {

namespace {
std::int64_t widen(FieldType t, std::uint32_t raw) noexcept {
  switch (t) {
    case FieldType::I8: return static_cast<std::int8_t>(static_cast<std::uint8_t>(raw));
    case FieldType::I32: return static_cast<std::int32_t>(raw);
    case FieldType::U8:
    case FieldType::U16:
    case FieldType::U32: return static_cast<std::int64_t>(raw);
  }
  return 0;
}
}  // namespace

void encode_record(const ParameterSet& set, std::uint32_t sequence, std::span<std::uint8_t, kRecordSize> out) noexcept {
  for (const MapEntry& e : kItemMap) {
    std::int64_t v = 0;
    if (e.id == ParamId::Sequence) {
      v = sequence;
    } else if (e.id == ParamId::LayoutVersion) {
      v = e.def;
    } else if (e.id == ParamId::Crc) {
      continue;
    } else {
      v = get_field(set, e.id).value_or(0);
    }
    // Two's complement truncation is the storage format of the signed items.
    put_le(out, e.offset, e.length, static_cast<std::uint32_t>(static_cast<std::uint64_t>(v) & 0xFFFF'FFFFU));
  }
  put_le(out, kCrcOffset, 4, crc32(std::span<const std::uint8_t>(out.data(), kCrcOffset)));
}

DecodeResult decode_record(std::span<const std::uint8_t, kRecordSize> in) noexcept {
  DecodeResult r{RecordStatus::BadCrc, ParamId::Crc, ParameterSet{}, 0};
  if (crc32(in.first(kCrcOffset)) != get_le(in, kCrcOffset, 4)) return r;
  ParameterSet s{};
  for (const MapEntry& e : kItemMap) {
    if (e.id == ParamId::Crc) continue;
    const std::int64_t v = widen(e.type, get_le(in, e.offset, e.length));
    if (check_item(e.id, v) != ValidationError::None) {
      r.status = RecordStatus::BadValue;
      r.bad_item = e.id;
      return r;
    }
    if (e.id == ParamId::Sequence) {
      r.sequence = static_cast<std::uint32_t>(v);
    } else if (e.role != Role::Meta) {
      (void)set_field(s, e.id, v);
    }
  }
  const Validation val = validate(s);
  if (!val.ok()) {
    r.status = RecordStatus::BadValue;
    r.bad_item = val.id;
    return r;
  }
  r.status = RecordStatus::Valid;
  r.set = s;
  return r;
}

}  // namespace ap::xy_storage
