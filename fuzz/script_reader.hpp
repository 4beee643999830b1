#pragma once
// The fuzz targets that decode a script of events from the input (board, axis_step, store_ops)
// read it through this: little-endian fields, and zeros once the input is used up, so every
// byte string is a complete script.
#include <cstddef>
#include <cstdint>

namespace ap::fuzz {

struct Reader {
  const std::uint8_t* p;
  std::size_t n;
  std::size_t i = 0;
  bool more() const { return i < n; }
  std::uint8_t u8() { return i < n ? p[i++] : 0; }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(u16()) | (static_cast<std::uint32_t>(u16()) << 16); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
};

}  // namespace ap::fuzz
