#pragma once
// The platform rotation (seed-000 §4.15: the gyro's z-rate integrated numerically) as an
// integer angle in m°, always in [0, 360000), with no arithmetic drift: the integral is kept
// exactly, remainder included, in units of 1/num m° (docs/sensors.md "Rotation").
//
// The gyro's sensitivity is num/den LSB per °/s (DS-000169 Table 1: 131, 65.5, 32.8, 16.4
// LSB/(°/s)). One sample per 1 ms control tick turns the platform by raw * den / num m°, i.e.
// by exactly raw * den units of 1/num m°. A full turn is 360000 * num units.
// Ranges: raw in [-32768, 32767], den <= 5, so one step is at most 163840 units in
// magnitude; a full turn is at most 360000 * 164 = 59,040,000 units: int32 throughout.
#include <cstdint>

namespace ap::xy_icm20789 {

enum class FullScale : std::uint8_t { Dps250 = 0, Dps500 = 1, Dps1000 = 2, Dps2000 = 3 };  // = FS_SEL

struct Sensitivity {
  std::int32_t num;  // LSB ...
  std::int32_t den;  // ... per den °/s
};

constexpr Sensitivity sensitivity(FullScale fs) {
  switch (fs) {
    case FullScale::Dps250: return {131, 1};
    case FullScale::Dps500: return {131, 2};   // 65.5
    case FullScale::Dps1000: return {164, 5};  // 32.8
    case FullScale::Dps2000: return {82, 5};   // 16.4
  }
  return {131, 1};
}

inline constexpr std::int32_t kFullTurnMdeg = 360000;
inline constexpr std::uint32_t kTickMs = 1;  // one sample per control tick (core/xy/axis)

class Rotation {
 public:
  explicit constexpr Rotation(FullScale fs = FullScale::Dps250)
      : num_(sensitivity(fs).num), den_(sensitivity(fs).den), turn_(kFullTurnMdeg * sensitivity(fs).num) {}

  // One control tick with the z-rate sample `raw` (GYRO_ZOUT, two's complement).
  constexpr void step(std::int16_t raw) {
    units_ += static_cast<std::int32_t>(raw) * den_;
    // |step| < turn_, so one correction brings units_ back into [0, turn_).
    if (units_ < 0) {
      units_ += turn_;
    } else if (units_ >= turn_) {
      units_ -= turn_;
    }
  }

  // Floor of the exact angle: units_ >= 0, so [0, 359999].
  constexpr std::int32_t mdeg() const { return units_ / num_; }

  // The exact angle as a fraction of a turn: units() / turn_units() turns.
  constexpr std::int32_t units() const { return units_; }
  constexpr std::int32_t turn_units() const { return turn_; }

  // Makes the present orientation 0 (the PC's "reference" of seed-000 §6 / §9.4.2).
  constexpr void zero() { units_ = 0; }

 private:
  std::int32_t num_;
  std::int32_t den_;
  std::int32_t turn_;
  std::int32_t units_ = 0;
};

}  // namespace ap::xy_icm20789
