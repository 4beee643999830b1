#pragma once
// Command frame parser and formatter (layout: codec/layout.hpp, docs/protocol.md).
#include <cstdint>
#include <span>

#include "codec/layout.hpp"
#include "core/frame/frames.hpp"

namespace ap::frame {

using CommandBytes = std::span<std::uint8_t, codec::kCommandLength>;

// Checks in wire order: length, start, end, characters, CRC, then IDs and ranges, so a
// semantic error is only ever reported for a frame whose CRC proved it arrived intact.
// On error `out` is untouched.
Rejection parse_command(std::span<const std::uint8_t> bytes, CommandFrame& out);

// Table checks only (IDs known, data and arguments in range, seq < 1000); the offset
// names the field that would carry the bad value.
Rejection validate(const CommandFrame& frame);

// Writes all kCommandLength bytes, or nothing when validate() fails.
Rejection format_command(const CommandFrame& frame, CommandBytes out);

}  // namespace ap::frame
