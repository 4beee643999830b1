#include "core/xy/storage/parameters.hpp"

namespace ap::xy_storage {

namespace {
// Range checked by the caller; the casts only narrow to the field's declared type.
template <typename T>
T narrow(std::int64_t v) noexcept {
  return static_cast<T>(v);
}
}  // namespace

bool set_field(ParameterSet& s, ParamId id, std::int64_t value) noexcept {
  if (entry(id).role == Role::Meta) return false;
  if (check_item(id, value) != ValidationError::None) return false;
  switch (id) {
    case ParamId::MaxAcceleration: s.max_acceleration_um_s2 = narrow<std::uint32_t>(value); break;
    case ParamId::FastSpeed: s.fast_speed_um_s = narrow<std::uint32_t>(value); break;
    case ParamId::SlowSpeed: s.slow_speed_um_s = narrow<std::uint32_t>(value); break;
    case ParamId::StartSpeed: s.start_speed_um_s = narrow<std::uint32_t>(value); break;
    case ParamId::LeadPitch: s.lead_pitch_um = narrow<std::uint32_t>(value); break;
    case ParamId::StepsPerRev: s.steps_per_rev = narrow<std::uint16_t>(value); break;
    case ParamId::Microsteps: s.microsteps = narrow<std::uint16_t>(value); break;
    case ParamId::RunCurrent: s.run_current_cs = narrow<std::uint8_t>(value); break;
    case ParamId::HoldCurrent: s.hold_current_cs = narrow<std::uint8_t>(value); break;
    case ParamId::HomingMode: s.homing_mode = narrow<std::uint8_t>(value); break;
    case ParamId::StallGuardThreshold: s.stallguard_threshold = narrow<std::int8_t>(value); break;
    case ParamId::SoftMinX: s.soft_min_x_um = narrow<std::int32_t>(value); break;
    case ParamId::SoftMaxX: s.soft_max_x_um = narrow<std::int32_t>(value); break;
    case ParamId::SoftMinY: s.soft_min_y_um = narrow<std::int32_t>(value); break;
    case ParamId::SoftMaxY: s.soft_max_y_um = narrow<std::int32_t>(value); break;
    case ParamId::HomingSpeed: s.homing_speed_um_s = narrow<std::uint32_t>(value); break;
    case ParamId::HomingBackoff: s.homing_backoff_um = narrow<std::uint32_t>(value); break;
    case ParamId::HomeOffsetX: s.home_offset_x_um = narrow<std::int32_t>(value); break;
    case ParamId::HomeOffsetY: s.home_offset_y_um = narrow<std::int32_t>(value); break;
    case ParamId::LowBatteryMv: s.low_battery_mv = narrow<std::uint16_t>(value); break;
    case ParamId::StepCountValid: s.step_counts_valid = value != 0; break;
    case ParamId::StepCountX: s.step_count_x = narrow<std::int32_t>(value); break;
    case ParamId::StepCountY: s.step_count_y = narrow<std::int32_t>(value); break;
    case ParamId::LayoutVersion:
    case ParamId::Sequence:
    case ParamId::Crc: return false;
  }
  return true;
}

ParameterSet defaults() noexcept {
  ParameterSet s{};
  for (const MapEntry& e : kItemMap) {
    if (e.role != Role::Meta) (void)set_field(s, e.id, e.def);
  }
  return s;
}

}  // namespace ap::xy_storage
