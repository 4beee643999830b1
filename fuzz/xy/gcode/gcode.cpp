// Fuzz target gcode_parser: bytes split at '\n' into lines; each line parsed in both
// dialects (docs/gcode.md) and the Tolerant block applied to one interpreter. Oracles
// (abort on violation), beyond the sanitizers:
//   - an error's column is 1..length+1 (length capped at kMaxLineLength), 0 on success,
//     and its line is the line number; a rejected line gives an empty Block;
//   - a line the Thesis dialect accepts, the Tolerant dialect accepts with the same Block
//     and the same columns (the Thesis syntax is a subset, docs/gcode.md §Dialects);
//   - a failed apply changes no interpreter state and returns an empty Move;
//   - every Move coordinate and arc centre is within +-kMaxPositionUm, the feed within
//     0..kMaxFeedUmS, a Move starts where the previous state was and ends at the new one.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/xy/gcode/interpreter.hpp"
#include "core/xy/gcode/parser.hpp"

namespace {

using namespace ap::xy_gcode;

void check(bool ok) {
  if (!ok) std::abort();
}

bool in_range(std::int32_t v) { return v >= -kMaxPositionUm && v <= kMaxPositionUm; }

void check_error(const ParseResult& r, std::size_t length, std::uint32_t line_no) {
  check(r.error.line == line_no);
  if (r.error.ok()) {
    check(r.error.column == 0);
    return;
  }
  const std::size_t limit = (length < kMaxLineLength ? length : kMaxLineLength) + 1;
  check(r.error.column >= 1 && r.error.column <= limit);
  check(r.block == Block{});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  Interpreter interp;
  std::uint32_t line_no = 0;
  std::size_t start = 0;
  while (start <= all.size()) {
    std::size_t nl = all.find('\n', start);
    if (nl == std::string_view::npos) nl = all.size();
    const std::string_view line = all.substr(start, nl - start);
    ++line_no;

    const ParseResult thesis = parse_line(line, line_no, Dialect::Thesis);
    const ParseResult tolerant = parse_line(line, line_no, Dialect::Tolerant);
    check_error(thesis, line.size(), line_no);
    check_error(tolerant, line.size(), line_no);
    if (thesis.error.ok()) {
      check(tolerant.error.ok());
      check(tolerant.block == thesis.block);
      check(tolerant.block.column == thesis.block.column);
      check(tolerant.block.motion_column == thesis.block.motion_column);
    }

    if (tolerant.error.ok()) {
      const State before = interp.state();
      const StepResult r = interp.apply(tolerant.block);
      check(r.error.line == line_no);
      if (!r.error.ok()) {
        check(interp.state() == before);
        check(r.move == Move{});
        check(r.error.column >= 1 && r.error.column <= line.size() + 1);
      } else {
        check(r.move.from == before.pos);
        check(r.move.to == interp.state().pos);
        check(r.move.line == line_no);
        for (int k = 0; k < 3; ++k) {
          check(in_range(r.move.from[static_cast<std::size_t>(k)]));
          check(in_range(r.move.to[static_cast<std::size_t>(k)]));
        }
        check(in_range(r.move.centre_x) && in_range(r.move.centre_y));
        check(r.move.feed_um_s >= 0 && r.move.feed_um_s <= kMaxFeedUmS);
        check(interp.state().feed_um_s >= 0 && interp.state().feed_um_s <= kMaxFeedUmS);
      }
    }
    start = nl + 1;
  }
  return 0;
}
