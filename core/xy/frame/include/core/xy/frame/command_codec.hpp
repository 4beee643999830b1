#pragma once
// Command frame parser and formatter (layout: codec/layout.hpp, docs/protocol.md).
#include <cstdint>
#include <span>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/frames.hpp"

namespace ap::xy_frame {

using CommandBytes = std::span<std::uint8_t, xy_codec::kCommandLength>;

// Checks in wire order: length, start, end, characters, CRC, then IDs and ranges, so a
// semantic error is only ever reported for a frame whose CRC proved it arrived intact.
// On error `out` is untouched.
Rejection parse_command(std::span<const std::uint8_t> bytes, CommandFrame& out);

// The link layer only: length, start, end, characters and CRC, so `out` holds what was
// sent, but its command IDs, data and subscriber slots are NOT checked against the tables
// (a two-digit ID may be 00..99). The board's receive path uses this, Klipper style: what a
// frame means is the callback table's business (CallbackTable::lookup), and the table's own
// bound check is what rejects an ID outside it. parse_command = decode_command + validate.
Rejection decode_command(std::span<const std::uint8_t> bytes, CommandFrame& out);

// Table checks only (IDs known, data and arguments in range, seq < 1000); the offset
// names the field that would carry the bad value.
Rejection validate(const CommandFrame& frame);

// Writes all kCommandLength bytes, or nothing when validate() fails.
Rejection format_command(const CommandFrame& frame, CommandBytes out);

}  // namespace ap::xy_frame
