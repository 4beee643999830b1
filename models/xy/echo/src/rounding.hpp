// The integer roundings the documents prescribe, shared by the parameter conversions
// (parameters.cpp) and the sensors (sensors.cpp); a private header of models/xy/echo/src, not
// part of the model's interface. Nearest with halves away from zero: um -> usteps
// (docs/motion.md §10 "Units and rounding") and the TMP117's code -> m°C (docs/sensors.md
// "TMP117"); floor and ceiling: the inward-rounded soft limits (motion.md §10) and the
// rotation's m° from the summed gyro codes (docs/sensors.md "Rotation: integration and wrap").
#pragma once

#include <cstdint>
#include <cstdlib>

namespace ap::model::xy_echo {

inline std::int64_t div_round_nearest(std::int64_t num, std::int64_t den) {  // den > 0, half away from zero
  const std::int64_t q = (std::llabs(num) * 2 + den) / (2 * den);
  return num < 0 ? -q : q;
}
inline std::int64_t div_floor(std::int64_t num, std::int64_t den) {
  std::int64_t q = num / den;
  if ((num % den != 0) && (num < 0)) --q;
  return q;
}
inline std::int64_t div_ceil(std::int64_t num, std::int64_t den) { return -div_floor(-num, den); }

}  // namespace ap::model::xy_echo
