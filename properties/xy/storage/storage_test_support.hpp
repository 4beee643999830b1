#pragma once
// Shared helpers for the storage suites: generators of valid sets and chip images.
#include <rapidcheck.h>

#include <algorithm>
#include <cstdint>

#include "core/xy/storage/fram_map.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/record.hpp"

namespace ap::xy_storage::test {

// RapidCheck's inRange leans towards its lower bound while the size is small; these draw
// evenly so mid-range values and later branches are reached from the first case on.
inline int pick(int n) { return *rc::gen::resize(100, rc::gen::inRange(0, n)); }
inline std::int64_t uniform(std::int64_t lo, std::int64_t hi_inclusive) {
  return *rc::gen::resize(100, rc::gen::inRange<std::int64_t>(lo, hi_inclusive + 1));
}

// A value for one item: its bounds often, uniform otherwise; powers of two for microsteps.
inline std::int64_t gen_item_value(const MapEntry& e) {
  if (e.rule == Rule::PowerOfTwo) {
    return std::int64_t{1} << pick(9);
  }
  switch (pick(4)) {
    case 0: return e.min;
    case 1: return e.max;
    default: return uniform(e.min, e.max);
  }
}

// A random set that passes validate(): every item in range, then the cross rules repaired.
inline ParameterSet gen_valid_set() {
  ParameterSet s = defaults();
  for (const MapEntry& e : kItemMap) {
    if (e.role == Role::Meta) continue;
    RC_ASSERT(set_field(s, e.id, gen_item_value(e)));
  }
  std::array<std::uint32_t, 3> sp{s.start_speed_um_s, s.slow_speed_um_s, s.fast_speed_um_s};
  std::sort(sp.begin(), sp.end());
  s.start_speed_um_s = sp[0];
  s.slow_speed_um_s = std::max<std::uint32_t>(sp[1], 1);
  s.fast_speed_um_s = std::max<std::uint32_t>(sp[2], 1);
  s.homing_speed_um_s = std::min(s.homing_speed_um_s, s.fast_speed_um_s);
  auto order = [](std::int32_t& lo, std::int32_t& hi) {
    if (lo > hi) std::swap(lo, hi);
    if (lo == hi) {
      if (hi < kWireMax) ++hi; else --lo;
    }
  };
  order(s.soft_min_x_um, s.soft_max_x_um);
  order(s.soft_min_y_um, s.soft_max_y_um);
  RC_ASSERT(validate(s).ok());
  return s;
}

}  // namespace ap::xy_storage::test
