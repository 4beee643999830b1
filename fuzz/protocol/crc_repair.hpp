#pragma once
// Shared by the protocol fuzz targets: a libFuzzer custom mutator that, after the default
// mutation, rewrites the CRC field of every complete frame-shaped run in the input (start
// character followed by a full frame's worth of bytes). Three times out of four only, so
// bad-CRC paths stay covered too. The CRC check in core is never bypassed.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "codec/layout.hpp"
#include "core/frame/fields.hpp"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size)
    __attribute__((weak));

namespace ap::fuzz {

inline void repair_crcs(std::uint8_t* data, std::size_t size) {
  const std::span<std::uint8_t> all(data, size);
  for (std::size_t i = 0; i < size; ++i) {
    std::size_t length = 0;
    std::size_t crc_offset = 0;
    if (data[i] == static_cast<std::uint8_t>(codec::kCommandStart)) {
      length = codec::kCommandLength;
      crc_offset = codec::kCommandCrcOffset;
    } else if (data[i] == static_cast<std::uint8_t>(codec::kEchoStart)) {
      length = codec::kEchoLength;
      crc_offset = codec::kEchoCrcOffset;
    } else {
      continue;
    }
    if (size - i < length) continue;
    const auto frame = all.subspan(i, length);
    frame::fields::write_hex16(frame, crc_offset, frame::fields::payload_crc(frame, crc_offset));
  }
}

// Fails the fuzz run (and the replay ctest) when an oracle does not hold.
inline void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace ap::fuzz

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  if (LLVMFuzzerMutate == nullptr) return size;
  size = LLVMFuzzerMutate(data, size, max_size);
  if ((seed & 3U) != 0) ap::fuzz::repair_crcs(data, size);
  return size;
}
