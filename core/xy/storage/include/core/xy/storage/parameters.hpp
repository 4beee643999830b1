#pragma once
// The parameter set the board keeps in FRAM. Units are the wire units (µm, µm/s, µm/s²,
// seed gap G4) so nothing is converted between the PC, the echo and the FRAM; the board
// supervisor converts to the axis module's microstep units. Ranges live in fram_map.hpp.
#include <bit>
#include <cstdint>
#include <optional>

#include "core/xy/storage/fram_map.hpp"

namespace ap::xy_storage {

struct ParameterSet {
  std::uint32_t max_acceleration_um_s2;
  std::uint32_t fast_speed_um_s;
  std::uint32_t slow_speed_um_s;
  std::uint32_t start_speed_um_s;
  std::uint32_t lead_pitch_um;
  std::uint16_t steps_per_rev;
  std::uint16_t microsteps;
  std::uint8_t run_current_cs;   // TMC2130 IHOLD_IRUN current scale 0..31
  std::uint8_t hold_current_cs;  // TMC2130 IHOLD_IRUN current scale 0..31
  std::uint8_t homing_mode;      // 0 none, 1 towards the min endstop, 2 StallGuard
  std::int8_t stallguard_threshold;
  std::int32_t soft_min_x_um;
  std::int32_t soft_max_x_um;
  std::int32_t soft_min_y_um;
  std::int32_t soft_max_y_um;
  std::uint32_t homing_speed_um_s;
  std::uint32_t homing_backoff_um;
  std::int32_t home_offset_x_um;
  std::int32_t home_offset_y_um;
  std::uint16_t low_battery_mv;
  // Set only by an orderly shutdown and cleared (in FRAM) before any motion starts: the
  // platform may be moved by hand while off, so a counter is trusted only if nothing could
  // have moved between the shutdown that wrote it and this boot (seed §4.11 caveat).
  bool step_counts_valid;
  std::int32_t step_count_x;  // microsteps
  std::int32_t step_count_y;  // microsteps

  friend constexpr bool operator==(const ParameterSet&, const ParameterSet&) = default;
};

// The value of a non-meta item, widened; std::nullopt for Meta items (layout version,
// sequence, CRC), which belong to a record and not to a set.
constexpr std::optional<std::int64_t> get_field(const ParameterSet& s, ParamId id) noexcept {
  switch (id) {
    case ParamId::MaxAcceleration: return s.max_acceleration_um_s2;
    case ParamId::FastSpeed: return s.fast_speed_um_s;
    case ParamId::SlowSpeed: return s.slow_speed_um_s;
    case ParamId::StartSpeed: return s.start_speed_um_s;
    case ParamId::LeadPitch: return s.lead_pitch_um;
    case ParamId::StepsPerRev: return s.steps_per_rev;
    case ParamId::Microsteps: return s.microsteps;
    case ParamId::RunCurrent: return s.run_current_cs;
    case ParamId::HoldCurrent: return s.hold_current_cs;
    case ParamId::HomingMode: return s.homing_mode;
    case ParamId::StallGuardThreshold: return s.stallguard_threshold;
    case ParamId::SoftMinX: return s.soft_min_x_um;
    case ParamId::SoftMaxX: return s.soft_max_x_um;
    case ParamId::SoftMinY: return s.soft_min_y_um;
    case ParamId::SoftMaxY: return s.soft_max_y_um;
    case ParamId::HomingSpeed: return s.homing_speed_um_s;
    case ParamId::HomingBackoff: return s.homing_backoff_um;
    case ParamId::HomeOffsetX: return s.home_offset_x_um;
    case ParamId::HomeOffsetY: return s.home_offset_y_um;
    case ParamId::LowBatteryMv: return s.low_battery_mv;
    case ParamId::StepCountValid: return s.step_counts_valid ? 1 : 0;
    case ParamId::StepCountX: return s.step_count_x;
    case ParamId::StepCountY: return s.step_count_y;
    case ParamId::LayoutVersion:
    case ParamId::Sequence:
    case ParamId::Crc: return std::nullopt;
  }
  return std::nullopt;
}

// True when the value lies inside the item's table range (and rule) and was stored.
bool set_field(ParameterSet& s, ParamId id, std::int64_t value) noexcept;

enum class ValidationError : std::uint8_t {
  None,
  OutOfRange,    // outside the item's [min, max]
  NotPowerOfTwo, // microsteps must be a TMC2130 MRES value
  SpeedOrder,    // needs start <= slow <= fast and homing <= fast
  LimitOrder,    // needs soft_min < soft_max on each axis
};

struct Validation {
  ValidationError error;
  ParamId id;  // the first offending item (for a cross rule: the item that breaks it)
  constexpr bool ok() const noexcept { return error == ValidationError::None; }
};

// Checks one value against its table entry alone.
constexpr ValidationError check_item(ParamId id, std::int64_t value) noexcept {
  const MapEntry& e = entry(id);
  if (value < e.min || value > e.max) return ValidationError::OutOfRange;
  if (e.rule == Rule::PowerOfTwo && !std::has_single_bit(static_cast<std::uint64_t>(value))) {
    return ValidationError::NotPowerOfTwo;
  }
  return ValidationError::None;
}

// The whole-set check the store applies before every save and to every loaded copy, and the
// board supervisor may call on its own: every item in range, then the cross-item rules.
constexpr Validation validate(const ParameterSet& s) noexcept {
  for (const MapEntry& e : kItemMap) {
    const std::optional<std::int64_t> v = get_field(s, e.id);
    if (!v) continue;
    const ValidationError err = check_item(e.id, *v);
    if (err != ValidationError::None) return {err, e.id};
  }
  if (s.start_speed_um_s > s.slow_speed_um_s) return {ValidationError::SpeedOrder, ParamId::StartSpeed};
  if (s.slow_speed_um_s > s.fast_speed_um_s) return {ValidationError::SpeedOrder, ParamId::SlowSpeed};
  if (s.soft_min_x_um >= s.soft_max_x_um) return {ValidationError::LimitOrder, ParamId::SoftMinX};
  if (s.soft_min_y_um >= s.soft_max_y_um) return {ValidationError::LimitOrder, ParamId::SoftMinY};
  return {ValidationError::None, ParamId::MaxAcceleration};
}

// The compile-time defaults, taken from the map table so the two cannot disagree.
ParameterSet defaults() noexcept;

}  // namespace ap::xy_storage
