#pragma once
// The FRAM address map: one constexpr table is the single source of truth for where every
// stored item lives, how wide it is, its default and its allowed range. The encoder, the
// decoder, the range checks, docs/storage.md (checked by a test) and a later SMT proof of
// disjointness all read this table, so an item cannot be moved in one place only
// (the grbl #459 class of bug: an address-map overlap that silently corrupts a neighbour).
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace ap::xy_storage {

// The part we design for: Fujitsu MB85RS256B, 256 Kbit = 32 KiB SPI FRAM. Two address bytes
// (A15 ignored), writes take effect per byte with no page buffer and no write delay, which is
// why a power cut leaves a byte-exact prefix of a write and nothing else.
struct FramChip {
  std::string_view part;
  std::uint32_t size_bytes;
};
inline constexpr FramChip kChip{"Fujitsu MB85RS256B", 32768U};

// Every stored item, in address order. The numeric value is also the item's wire/parameter id.
enum class ParamId : std::uint8_t {
  MaxAcceleration = 0,
  FastSpeed,
  SlowSpeed,
  StartSpeed,
  LeadPitch,
  StepsPerRev,
  Microsteps,
  RunCurrent,
  HoldCurrent,
  HomingMode,
  StallGuardThreshold,
  SoftMinX,
  SoftMaxX,
  SoftMinY,
  SoftMaxY,
  HomingSpeed,
  HomingBackoff,
  HomeOffsetX,
  HomeOffsetY,
  LowBatteryMv,
  StepCountValid,
  LayoutVersion,
  StepCountX,
  StepCountY,
  Sequence,
  Crc,
};
inline constexpr std::size_t kItemCount = 26;

enum class FieldType : std::uint8_t { U8, I8, U16, U32, I32 };

// Who may change an item (thesis §7.5.4: "výrobné a užívateľské parametre", factory and user
// parameters; docs/storage.md "Factory and user parameters"): factory items describe the
// machine (screw, motor, driver currents, limits, homing) and are set by whoever builds the
// platform; user items are the motion settings an operator changes (speeds, acceleration).
// Both change through set_parameter(); the PC client sends a factory item only when opened
// for factory work. Step-counter items change through begin_motion / record_shutdown; meta
// items belong to the record; reserved items keep their slot in the layout and are never read
// or changed (the reason is in docs/storage.md).
enum class Role : std::uint8_t { Factory, User, StepCounter, Meta, Reserved };

// Extra rule on top of [min, max]; TMC2130 MRES only encodes powers of two.
enum class Rule : std::uint8_t { Range, PowerOfTwo };

struct MapEntry {
  ParamId id;
  std::string_view name;
  std::uint16_t offset;  // inside a record; copy A's record starts at 0x0000
  std::uint8_t length;   // bytes, least significant first
  FieldType type;
  Role role;
  Rule rule;
  std::int64_t def;
  std::int64_t min;
  std::int64_t max;
  std::string_view unit;
};

inline constexpr std::int64_t kI32Min = std::numeric_limits<std::int32_t>::min();
inline constexpr std::int64_t kI32Max = std::numeric_limits<std::int32_t>::max();
inline constexpr std::int64_t kU32Max = std::numeric_limits<std::uint32_t>::max();
// Six decimal digits: the widest value a protocol data field can carry (seed gap G4).
inline constexpr std::int64_t kWireMax = 999'999;

// Defaults are seed gap G10 decisions (the thesis gives none except 20000 µm/s² and the
// 10 mm/s of its tests); each is documented with its reason in docs/storage.md.
inline constexpr std::array<MapEntry, kItemCount> kItemMap{{
    {ParamId::MaxAcceleration, "max_acceleration", 0x00, 4, FieldType::U32, Role::User, Rule::Range, 20000, 1, kWireMax, "um/s2"},
    {ParamId::FastSpeed, "fast_speed", 0x04, 4, FieldType::U32, Role::User, Rule::Range, 10000, 1, kWireMax, "um/s"},
    {ParamId::SlowSpeed, "slow_speed", 0x08, 4, FieldType::U32, Role::User, Rule::Range, 2000, 1, kWireMax, "um/s"},
    {ParamId::StartSpeed, "start_speed", 0x0C, 4, FieldType::U32, Role::User, Rule::Range, 500, 0, kWireMax, "um/s"},
    {ParamId::LeadPitch, "lead_pitch", 0x10, 4, FieldType::U32, Role::Factory, Rule::Range, 2000, 100, 100'000, "um"},
    {ParamId::StepsPerRev, "steps_per_rev", 0x14, 2, FieldType::U16, Role::Factory, Rule::Range, 200, 1, 1000, "steps"},
    {ParamId::Microsteps, "microsteps", 0x16, 2, FieldType::U16, Role::Factory, Rule::PowerOfTwo, 16, 1, 256, "usteps/step"},
    {ParamId::RunCurrent, "run_current", 0x18, 1, FieldType::U8, Role::Factory, Rule::Range, 16, 0, 31, "CS"},
    {ParamId::HoldCurrent, "hold_current", 0x19, 1, FieldType::U8, Role::Factory, Rule::Range, 8, 0, 31, "CS"},
    {ParamId::HomingMode, "homing_mode", 0x1A, 1, FieldType::U8, Role::Factory, Rule::Range, 1, 0, 2, "enum"},
    {ParamId::StallGuardThreshold, "stallguard_threshold", 0x1B, 1, FieldType::I8, Role::Factory, Rule::Range, 0, -64, 63, "SGT"},
    {ParamId::SoftMinX, "soft_min_x", 0x1C, 4, FieldType::I32, Role::Factory, Rule::Range, 0, -kWireMax, kWireMax, "um"},
    {ParamId::SoftMaxX, "soft_max_x", 0x20, 4, FieldType::I32, Role::Factory, Rule::Range, 200'000, -kWireMax, kWireMax, "um"},
    {ParamId::SoftMinY, "soft_min_y", 0x24, 4, FieldType::I32, Role::Factory, Rule::Range, 0, -kWireMax, kWireMax, "um"},
    {ParamId::SoftMaxY, "soft_max_y", 0x28, 4, FieldType::I32, Role::Factory, Rule::Range, 200'000, -kWireMax, kWireMax, "um"},
    {ParamId::HomingSpeed, "homing_speed", 0x2C, 4, FieldType::U32, Role::Reserved, Rule::Range, 2000, 1, kWireMax, "um/s"},
    {ParamId::HomingBackoff, "homing_backoff", 0x30, 4, FieldType::U32, Role::Reserved, Rule::Range, 1000, 0, 100'000, "um"},
    {ParamId::HomeOffsetX, "home_offset_x", 0x34, 4, FieldType::I32, Role::Factory, Rule::Range, 0, -kWireMax, kWireMax, "um"},
    {ParamId::HomeOffsetY, "home_offset_y", 0x38, 4, FieldType::I32, Role::Factory, Rule::Range, 0, -kWireMax, kWireMax, "um"},
    {ParamId::LowBatteryMv, "low_battery", 0x3C, 2, FieldType::U16, Role::Factory, Rule::Range, 3300, 2500, 30000, "mV"},
    {ParamId::StepCountValid, "step_count_valid", 0x3E, 1, FieldType::U8, Role::StepCounter, Rule::Range, 0, 0, 1, "flag"},
    {ParamId::LayoutVersion, "layout_version", 0x3F, 1, FieldType::U8, Role::Meta, Rule::Range, 1, 1, 1, "-"},
    {ParamId::StepCountX, "step_count_x", 0x40, 4, FieldType::I32, Role::StepCounter, Rule::Range, 0, kI32Min, kI32Max, "usteps"},
    {ParamId::StepCountY, "step_count_y", 0x44, 4, FieldType::I32, Role::StepCounter, Rule::Range, 0, kI32Min, kI32Max, "usteps"},
    {ParamId::Sequence, "sequence", 0x48, 4, FieldType::U32, Role::Meta, Rule::Range, 0, 0, kU32Max, "-"},
    {ParamId::Crc, "crc32", 0x4C, 4, FieldType::U32, Role::Meta, Rule::Range, 0, 0, kU32Max, "-"},
}};

// One record = one complete parameter set + sequence + CRC-32 over everything before the CRC.
inline constexpr std::size_t kRecordSize = 0x50;
inline constexpr std::size_t kCrcOffset = 0x4C;
inline constexpr std::size_t kCopyCount = 2;
// Copy B sits on the next 256-byte boundary so records can grow to 0x100 bytes without moving.
inline constexpr std::array<std::uint16_t, kCopyCount> kCopyBase{0x0000, 0x0100};

// An absolute FRAM region: one item of one copy.
struct Region {
  ParamId id;
  std::uint8_t copy;  // 0 = A, 1 = B
  std::uint32_t start;
  std::uint32_t length;
};

namespace detail {
constexpr std::array<Region, kItemCount * kCopyCount> make_absolute_map() noexcept {
  std::array<Region, kItemCount * kCopyCount> out{};
  std::size_t n = 0;
  for (std::size_t c = 0; c < kCopyCount; ++c) {
    for (const MapEntry& e : kItemMap) {
      out[n++] = Region{e.id, static_cast<std::uint8_t>(c), static_cast<std::uint32_t>(kCopyBase[c]) + e.offset,
                        e.length};
    }
  }
  return out;
}

constexpr std::uint8_t width_of(FieldType t) noexcept {
  switch (t) {
    case FieldType::U8:
    case FieldType::I8: return 1;
    case FieldType::U16: return 2;
    case FieldType::U32:
    case FieldType::I32: return 4;
  }
  return 0;
}

constexpr std::int64_t type_min(FieldType t) noexcept {
  switch (t) {
    case FieldType::I8: return -128;
    case FieldType::I32: return kI32Min;
    case FieldType::U8:
    case FieldType::U16:
    case FieldType::U32: return 0;
  }
  return 0;
}

constexpr std::int64_t type_max(FieldType t) noexcept {
  switch (t) {
    case FieldType::U8: return 255;
    case FieldType::I8: return 127;
    case FieldType::U16: return 65535;
    case FieldType::U32: return kU32Max;
    case FieldType::I32: return kI32Max;
  }
  return 0;
}
}  // namespace detail

inline constexpr std::array<Region, kItemCount * kCopyCount> kAbsoluteMap = detail::make_absolute_map();

// The accessors a proof or a report uses; the same storage the firmware reads.
constexpr std::span<const Region, kItemCount * kCopyCount> address_map() noexcept { return kAbsoluteMap; }
constexpr const MapEntry& entry(ParamId id) noexcept { return kItemMap[static_cast<std::size_t>(id)]; }

constexpr bool regions_disjoint(std::span<const Region> regions) noexcept {
  for (std::size_t i = 0; i < regions.size(); ++i) {
    for (std::size_t j = i + 1; j < regions.size(); ++j) {
      const Region& a = regions[i];
      const Region& b = regions[j];
      if (a.start < b.start + b.length && b.start < a.start + a.length) return false;
    }
  }
  return true;
}

constexpr bool regions_fit_chip(std::span<const Region> regions) noexcept {
  for (const Region& r : regions) {
    if (r.length == 0 || r.start + r.length > kChip.size_bytes) return false;
  }
  return true;
}

namespace detail {
constexpr bool table_is_indexed_by_id() noexcept {
  for (std::size_t i = 0; i < kItemMap.size(); ++i) {
    if (static_cast<std::size_t>(kItemMap[i].id) != i) return false;
  }
  return true;
}

constexpr bool entries_well_formed() noexcept {
  for (const MapEntry& e : kItemMap) {
    if (e.length != width_of(e.type)) return false;
    if (e.min > e.max || e.def < e.min || e.def > e.max) return false;
    if (e.min < type_min(e.type) || e.max > type_max(e.type)) return false;
  }
  return true;
}

// Every byte of a record belongs to exactly one item: no gaps whose content would be undefined.
constexpr bool record_tiled() noexcept {
  std::size_t total = 0;
  for (const MapEntry& e : kItemMap) {
    if (e.offset + e.length > kRecordSize) return false;
    total += e.length;
  }
  return total == kRecordSize;
}

constexpr bool records_disjoint_and_fit() noexcept {
  for (std::size_t c = 0; c < kCopyCount; ++c) {
    if (kCopyBase[c] + kRecordSize > kChip.size_bytes) return false;
    for (std::size_t d = c + 1; d < kCopyCount; ++d) {
      if (kCopyBase[c] < kCopyBase[d] + kRecordSize && kCopyBase[d] < kCopyBase[c] + kRecordSize) return false;
    }
  }
  return true;
}
}  // namespace detail

static_assert(detail::table_is_indexed_by_id(), "kItemMap must list items in ParamId order");
static_assert(detail::entries_well_formed(), "an item's width, default or range does not fit its type");
static_assert(regions_disjoint(kAbsoluteMap), "two FRAM items overlap");
static_assert(regions_fit_chip(kAbsoluteMap), "a FRAM item lies outside the chip");
static_assert(detail::record_tiled(), "record items must tile the record exactly");
static_assert(detail::records_disjoint_and_fit(), "copies A and B overlap or leave the chip");
static_assert(kItemMap[static_cast<std::size_t>(ParamId::Crc)].offset == kCrcOffset &&
                  kCrcOffset + 4 == kRecordSize,
              "the CRC must be the record's last field");
// The thesis test (§9.2): maximum acceleration is stored from address 0x0000.
static_assert(kCopyBase[0] + kItemMap[0].offset == 0x0000 && kItemMap[0].id == ParamId::MaxAcceleration);

}  // namespace ap::xy_storage
