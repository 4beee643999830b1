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
  // One read per statement: the operands of `u8() | (u8() << 8)` are unsequenced, and gcc and
  // clang read them in opposite orders, so a reproducer found by the clang fuzzer meant another
  // script in the gcc replay.
  std::uint16_t u16() {
    const std::uint16_t lo = u8();
    const std::uint16_t hi = u8();
    return static_cast<std::uint16_t>(lo | (hi << 8));
  }
  std::uint32_t u32() {
    const std::uint32_t lo = u16();
    const std::uint32_t hi = u16();
    return lo | (hi << 16);
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
};

}  // namespace ap::fuzz
