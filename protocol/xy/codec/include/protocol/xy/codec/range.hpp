#pragma once
// Inclusive integer range used by every table entry, so one check serves commands,
// statuses and subscribers alike.
#include <cstdint>

namespace ap::xy_codec {

struct Range {
  std::int32_t min;
  std::int32_t max;
  constexpr bool contains(std::int32_t v) const { return v >= min && v <= max; }
};

}  // namespace ap::xy_codec
