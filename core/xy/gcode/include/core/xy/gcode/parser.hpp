// G-code line parser: one line (without its '\n') into a Block, no heap, no floating point.
// Two dialects (docs/gcode.md §Dialects):
//   Thesis   - the thesis's syntax (seed-003.md §2.4): "N<digits> G<num>|M<num>[ <word>]...",
//              exactly one space between words, uppercase, no comments.
//   Tolerant - what grbl / LinuxCNC accept: optional N, any case, spaces/tabs (or none)
//              between words, (comments) and ';' comments, '%' lines, '+' signs, a final '\r',
//              blank lines (an empty Block).
// Every line the Thesis dialect accepts, the Tolerant dialect accepts with the same Block.
// Errors are checked in this order: length, characters, then words left to right.
#pragma once

#include <cstdint>
#include <string_view>

#include "core/xy/gcode/block.hpp"
#include "core/xy/gcode/error.hpp"

namespace ap::xy_gcode {

enum class Dialect : std::uint8_t { Thesis, Tolerant };

// Longest accepted line, in bytes (a '\r' counts). Columns therefore fit in uint16_t.
inline constexpr std::size_t kMaxLineLength = 256;

// On error, block is a default Block (with block.line = the line number) and error says why;
// on success error.kind == None, error.column == 0.
struct ParseResult {
  Block block;
  Error error;
};

ParseResult parse_line(std::string_view text, std::uint32_t line_no, Dialect d);

}  // namespace ap::xy_gcode
