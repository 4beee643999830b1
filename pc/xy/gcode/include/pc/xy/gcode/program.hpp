// A G-code program on the PC side (docs/cnc.md "From G-code to the axes"): every line parsed
// by core/xy/gcode (one dialect for the whole file), the moves turned into the board's path frames,
// and the look-ahead's report of each junction (core/xy/lookahead).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/xy/gcode/parser.hpp"
#include "protocol/xy/codec/commands.hpp"

namespace ap::xy_pcgcode {

// A line the core refused: file:line:column: the error's name.
class ProgramError : public std::runtime_error {
 public:
  ProgramError(const std::string& what, std::uint32_t line, std::uint16_t column)
      : std::runtime_error(what), line_(line), column_(column) {}
  [[nodiscard]] std::uint32_t line() const { return line_; }
  [[nodiscard]] std::uint16_t column() const { return column_; }

 private:
  std::uint32_t line_;
  std::uint16_t column_;
};

// One command frame: the X and the Y part (a unit command rides in the X part).
struct Frame {
  xy_codec::CommandId x_id = xy_codec::CommandId::Nop;
  std::int32_t x = 0;
  xy_codec::CommandId y_id = xy_codec::CommandId::Nop;
  std::int32_t y = 0;
  std::uint32_t line = 0;  // the G-code line it comes from (0: added by the translation)
};

enum class SegKind : std::uint8_t { Line, ArcCw, ArcCcw };

// A commanded XY segment in micrometres, as the program states it (the ideal path).
struct Segment {
  SegKind kind = SegKind::Line;
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0, cx = 0, cy = 0;
  std::uint32_t line = 0;
  bool rapid = false;
};

// The look-ahead at the junction after `segment`: the thesis's law (factor), the per-axis cap,
// and what the board does there (docs/cnc.md "Chains").
struct Junction {
  std::size_t segment = 0;        // index of the segment before it
  std::int32_t turn_mdeg = 0;
  std::uint16_t factor_permille = 0;
  std::string kind;               // straight, corner, stop, z-only stop
  std::uint32_t thesis_um_s = 0;  // factor * v_max
  std::uint32_t capped_um_s = 0;  // with the per-axis velocity jump <= v_jump
  bool continuous = false;        // the board keeps the speed (one chain)
};

struct Program {
  std::vector<Frame> frames;
  std::vector<Segment> segments;
  std::vector<Junction> junctions;
  std::vector<std::string> notes;  // lines the platform does not execute, and why
  std::int64_t end_x_um = 0, end_y_um = 0;
  std::size_t segment_frames = 0;  // frames that queue a segment on the board
};

struct Options {
  xy_gcode::Dialect dialect = xy_gcode::Dialect::Tolerant;
  std::uint32_t v_max_um_s = 50'000;  // for the junction report: the thesis's v_max
  std::uint32_t v_jump_um_s = 0;      // the axes' start speed (the jump a stepper follows)
};

// Throws ProgramError on the first line the core refuses, or a move the link cannot carry
// (an end or an arc centre outside 0..999999 um).
Program translate(std::string_view text, const Options& opt, const std::string& file = "<gcode>");

}  // namespace ap::xy_pcgcode
