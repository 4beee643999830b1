#pragma once
// Shared by the protocol fuzz targets: a libFuzzer custom mutator that, after the default
// mutation, rewrites the CRC field of every complete frame-shaped run in the input (start
// character followed by a full frame's worth of bytes). Three times out of four only, so
// bad-CRC paths stay covered too. The CRC check in core is never bypassed.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "protocol/xy/codec/crc16.hpp"
#include "protocol/xy/codec/layout.hpp"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size)
    __attribute__((weak));

// The mutator is not code under test, so it is built without coverage instrumentation and
// with a table-driven copy of the CRC: the instrumented bit-by-bit xy_codec::crc16 in the
// mutator cost about a quarter of the parser target's time (perf, fuzz preset) and filled
// libFuzzer's comparison table with the mutator's own compares. The frame's CRC is still
// checked by core's xy_codec::crc16; the two are tied together by the static_asserts below.
#if defined(__clang__)
#define AP_FUZZ_NOT_INSTRUMENTED __attribute__((no_sanitize("coverage", "address", "undefined")))
#else
#define AP_FUZZ_NOT_INSTRUMENTED
#endif

namespace ap::fuzz {

namespace detail {
// A plain array: an std::array::operator[] call would not be inlined into the
// uninstrumented function below (different sanitizer attributes) and costs a call per byte.
struct CrcTable {
  std::uint16_t v[256];  // NOLINT(*-avoid-c-arrays)
};
constexpr CrcTable crc_table() {
  CrcTable t{};
  for (std::size_t i = 0; i < 256; ++i) t.v[i] = xy_codec::crc16_update(0, static_cast<std::uint8_t>(i));
  return t;
}
inline constexpr CrcTable kCrcTable = crc_table();

AP_FUZZ_NOT_INSTRUMENTED constexpr std::uint16_t crc16(const std::uint8_t* p, std::size_t n) {
  std::uint16_t crc = xy_codec::kCrcInit;
  for (std::size_t i = 0; i < n; ++i) {
    crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable.v[static_cast<std::uint8_t>((crc >> 8) ^ p[i])]);
  }
  return crc;
}
constexpr std::array<std::uint8_t, 9> kCheck{'1', '2', '3', '4', '5', '6', '7', '8', '9'};
static_assert(crc16(kCheck.data(), kCheck.size()) == xy_codec::kCrcCheck);
static_assert(crc16(kCheck.data(), kCheck.size()) == xy_codec::crc16(kCheck));
constexpr std::array<std::uint8_t, 5> kMixed{0x00, 0xFF, '>', ';', 0x80};
static_assert(crc16(kMixed.data(), kMixed.size()) == xy_codec::crc16(kMixed));
}  // namespace detail

// Rewrites the CRC field (4 upper-case hex digits) of the frame starting at `frame`.
AP_FUZZ_NOT_INSTRUMENTED inline void write_crc(std::uint8_t* frame, std::size_t crc_offset) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const std::uint16_t crc = detail::crc16(frame + xy_codec::kStartWidth, crc_offset - xy_codec::kStartWidth);
  for (std::size_t k = 0; k < 4; ++k) frame[crc_offset + k] = static_cast<std::uint8_t>(kHex[(crc >> (12 - 4 * k)) & 0xFU]);
}

AP_FUZZ_NOT_INSTRUMENTED inline void repair_crcs(std::uint8_t* data, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    std::size_t length = 0;
    std::size_t crc_offset = 0;
    if (data[i] == static_cast<std::uint8_t>(xy_codec::kCommandStart)) {
      length = xy_codec::kCommandLength;
      crc_offset = xy_codec::kCommandCrcOffset;
    } else if (data[i] == static_cast<std::uint8_t>(xy_codec::kEchoStart)) {
      length = xy_codec::kEchoLength;
      crc_offset = xy_codec::kEchoCrcOffset;
    } else {
      continue;
    }
    if (size - i < length) continue;
    write_crc(data + i, crc_offset);
  }
}

// Fails the fuzz run (and the replay ctest) when an oracle does not hold.
inline void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace ap::fuzz

extern "C" AP_FUZZ_NOT_INSTRUMENTED std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  if (LLVMFuzzerMutate == nullptr) return size;
  size = LLVMFuzzerMutate(data, size, max_size);
  if ((seed & 3U) != 0) ap::fuzz::repair_crcs(data, size);
  return size;
}
