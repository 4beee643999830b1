// Two one-liners over points both halves of the executor use (segments.cpp, executor.cpp): a
// 64-bit absolute value and a point relative to a centre. A private header of core/xy/path/src,
// not part of the path's interface.
#pragma once

#include <array>
#include <cstdint>

#include "core/xy/path/executor.hpp"

namespace ap::xy_path {

constexpr std::int64_t abs64(std::int64_t v) { return v < 0 ? -v : v; }

inline std::array<std::int32_t, 2> rel(const Point& p, const Point& c) { return {p[0] - c[0], p[1] - c[1]}; }

}  // namespace ap::xy_path
