#include "pc/xy/gcode/program.hpp"

#include <algorithm>
#include <cstdio>

#include "core/xy/gcode/interpreter.hpp"
#include "core/xy/lookahead/junction.hpp"

namespace ap::xy_pcgcode {

namespace {

using xy_codec::CommandId;
namespace la = ap::xy_lookahead;

std::string where(const std::string& file, std::uint32_t line, std::uint16_t col) {
  return file + ":" + std::to_string(line) + ":" + std::to_string(col);
}

// The link carries six-character data fields (docs/protocol.md): the platform's commands take
// 0..999999 um for an end and -99999..999999 um for a centre offset.
void check_range(std::int64_t v, std::int64_t lo, std::int64_t hi, const std::string& file, std::uint32_t line,
                 const char* what) {
  if (v < lo || v > hi) {
    throw ProgramError(where(file, line, 1) + ": " + what + " " + std::to_string(v) + " um is outside " +
                           std::to_string(lo) + ".." + std::to_string(hi) + " um, what the platform's frames carry",
                       line, 1);
  }
}

la::Direction entry(const Segment& s) {
  if (s.kind == SegKind::Line) return la::line_direction(s.x1 - s.x0, s.y1 - s.y0, 0);
  return la::arc_start_direction(s.x0 - s.cx, s.y0 - s.cy, s.kind == SegKind::ArcCw ? la::Turn::Cw : la::Turn::Ccw);
}

la::Direction exit(const Segment& s) {
  if (s.kind == SegKind::Line) return la::line_direction(s.x1 - s.x0, s.y1 - s.y0, 0);
  return la::arc_end_direction(s.x1 - s.cx, s.y1 - s.cy, s.kind == SegKind::ArcCw ? la::Turn::Cw : la::Turn::Ccw);
}

const char* kind_name(la::JunctionKind k) {
  switch (k) {
    case la::JunctionKind::Straight: return "straight";
    case la::JunctionKind::Corner: return "corner";
    case la::JunctionKind::Stop: return "stop";
    case la::JunctionKind::ZOnlyStop: return "z-only stop";
    case la::JunctionKind::NoDirection: return "no direction";
    case la::JunctionKind::Invalid: return "invalid";
  }
  return "?";
}

}  // namespace

Program translate(std::string_view text, const Options& opt, const std::string& file) {
  Program p;
  xy_gcode::Interpreter interp;
  std::uint32_t line_no = 0;
  bool open_chain = false;   // segments queued since the last path_end
  bool z_break = false;      // a Z-only move since the last segment
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view raw = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (eol == text.size() && raw.empty()) break;  // the newline that ends the file
    const xy_gcode::ParseResult pr = xy_gcode::parse_line(raw, line_no, opt.dialect);
    if (!pr.error.ok()) {
      throw ProgramError(where(file, pr.error.line, pr.error.column) + ": " + xy_gcode::error_name(pr.error.kind),
                         pr.error.line, pr.error.column);
    }
    if (pr.block.has_m) {
      p.notes.push_back(where(file, line_no, 1) + ": M" + std::to_string(pr.block.m) +
                        " parsed, not executed (the thesis executes no M codes, seed-003.md §2.4)");
    }
    const xy_gcode::StepResult sr = interp.apply(pr.block);
    if (!sr.error.ok()) {
      throw ProgramError(where(file, sr.error.line, sr.error.column) + ": " + xy_gcode::error_name(sr.error.kind),
                         sr.error.line, sr.error.column);
    }
    const xy_gcode::Move& m = sr.move;
    if (m.kind == xy_gcode::MoveKind::None) continue;
    if (m.z_only) {
      // docs/cnc.md: the platform has no Z axis; a Z-only move is where a machine with one would
      // stand in XY, so the XY path ends at rest there (the look-ahead's ZOnlyStop).
      p.notes.push_back(where(file, line_no, 1) + ": Z-only move, no Z axis on the platform: the XY path stops here");
      if (open_chain) {
        p.frames.push_back({CommandId::PathEnd, 0, CommandId::Nop, 0, line_no});
        open_chain = false;
      }
      z_break = true;
      continue;
    }
    if (m.from[2] != m.to[2]) {
      p.notes.push_back(where(file, line_no, 1) + ": Z word ignored (no Z axis on the platform); XY executed");
    }
    Segment s;
    s.x0 = m.from[0];
    s.y0 = m.from[1];
    s.x1 = m.to[0];
    s.y1 = m.to[1];
    s.line = line_no;
    s.rapid = m.kind == xy_gcode::MoveKind::Rapid;
    if (m.kind == xy_gcode::MoveKind::ArcCw || m.kind == xy_gcode::MoveKind::ArcCcw) {
      s.kind = m.kind == xy_gcode::MoveKind::ArcCw ? SegKind::ArcCw : SegKind::ArcCcw;
      s.cx = m.centre_x;
      s.cy = m.centre_y;
    }
    if (s.x0 == s.x1 && s.y0 == s.y1 && s.kind == SegKind::Line) {
      p.notes.push_back(where(file, line_no, 1) + ": zero-length move dropped");
      continue;
    }
    check_range(s.x1, 0, 999999, file, line_no, "X end");
    check_range(s.y1, 0, 999999, file, line_no, "Y end");
    if (!p.segments.empty()) {
      const Segment& prev = p.segments.back();
      Junction j;
      j.segment = p.segments.size() - 1;
      const la::Junction lj = z_break ? la::junction(la::line_direction(0, 0, 1), entry(s))
                                      : la::junction(exit(prev), entry(s));
      j.turn_mdeg = lj.turn_mdeg;
      j.factor_permille = lj.factor_permille;
      j.kind = kind_name(lj.kind);
      j.thesis_um_s = static_cast<std::uint32_t>(static_cast<std::uint64_t>(opt.v_max_um_s) * lj.factor_permille / 1000U);
      j.capped_um_s = z_break ? 0 : la::junction_speed(opt.v_max_um_s, lj, exit(prev), entry(s), opt.v_jump_um_s);
      j.continuous = !z_break && lj.kind == la::JunctionKind::Straight;
      p.junctions.push_back(j);
    }
    if (s.kind == SegKind::Line) {
      p.frames.push_back({CommandId::PathLine, static_cast<std::int32_t>(s.x1), CommandId::PathLine,
                          static_cast<std::int32_t>(s.y1), line_no});
    } else {
      check_range(s.cx, 0, 999999, file, line_no, "arc centre X");
      check_range(s.cy, 0, 999999, file, line_no, "arc centre Y");
      p.frames.push_back({CommandId::PathCentre, static_cast<std::int32_t>(s.cx), CommandId::PathCentre,
                          static_cast<std::int32_t>(s.cy), line_no});
      const CommandId id = s.kind == SegKind::ArcCw ? CommandId::PathArcCw : CommandId::PathArcCcw;
      p.frames.push_back({id, static_cast<std::int32_t>(s.x1), id, static_cast<std::int32_t>(s.y1), line_no});
    }
    ++p.segment_frames;
    p.segments.push_back(s);
    open_chain = true;
    z_break = false;
    p.end_x_um = s.x1;
    p.end_y_um = s.y1;
  }
  if (open_chain) p.frames.push_back({CommandId::PathEnd, 0, CommandId::Nop, 0, 0});
  return p;
}

}  // namespace ap::xy_pcgcode
