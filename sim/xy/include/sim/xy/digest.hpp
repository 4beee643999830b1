// The digest the simulated board and the simulated PC each keep of a byte stream, and compare
// at the end of a run: the frames the board took against the frames the client saw answered
// (docs/sim.md "Delivery check"), the board's TX stream against the echoes the bus brought
// (docs/sim.md "Echo checks"). A header of its own so that the PC side reaches it without the
// board's header (sim/xy/board.hpp).
#pragma once

#include <cstdint>
#include <span>

namespace ap::sim::xy {

// FNV-1a 64 (offset basis, prime): a digest of a byte stream, extended byte by byte.
inline constexpr std::uint64_t kFnvBasis = 0xcbf29ce484222325ULL;
constexpr std::uint64_t fnv1a(std::uint64_t h, std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ULL;
  return h;
}

}  // namespace ap::sim::xy
