// Modal interpreter (docs/gcode.md §Interpreter). Works on a copy of the state and commits
// it only when the whole line is valid, so a rejected line changes nothing.
#include "core/xy/gcode/interpreter.hpp"

#include <cstddef>
#include <cstdint>
#include <initializer_list>

#include "core/xy/gcode/arc.hpp"

namespace ap::xy_gcode {
namespace {

bool in_range(std::int64_t v) { return v >= -kMaxPositionUm && v <= kMaxPositionUm; }

// Column of the leftmost of the given present words (0 if none is present).
std::uint16_t first_column(const Block& b, std::initializer_list<Word> words) {
  std::uint16_t best = 0;
  for (const Word w : words) {
    if (b.has(w) && (best == 0 || b.col(w) < best)) best = b.col(w);
  }
  return best;
}

constexpr bool is_arc(Motion m) { return m == Motion::ArcCw || m == Motion::ArcCcw; }

std::int64_t square(std::int64_t v) { return v * v; }

}  // namespace

StepResult Interpreter::apply(const Block& b) {
  const auto fail = [&b](ErrorKind k, std::uint16_t column) {
    StepResult r;
    r.error = Error{k, b.line, column};
    return r;
  };

  // Modal words first, in grbl's order: units and distance mode apply to every number on
  // the same line, F included (docs/gcode.md §Units).
  State next = state_;
  if (b.units != Units::Unchanged) next.inches = b.units == Units::Inch;
  if (b.distance != Distance::Unchanged) next.incremental = b.distance == Distance::Incremental;
  if (b.has(Word::F)) {
    const std::int32_t f = feed_um_s(b.get(Word::F), next.inches);
    if (f <= 0) return fail(ErrorKind::BadFeed, b.col(Word::F));
    next.feed_um_s = f;
  }
  if (b.motion != Motion::None) next.motion = b.motion;

  StepResult out;
  out.error.line = b.line;
  Move& m = out.move;
  m.line = b.line;
  m.n = b.has_n ? static_cast<std::int32_t>(b.n) : -1;
  m.from = state_.pos;
  m.to = state_.pos;

  const bool centre_words = b.has(Word::I) || b.has(Word::J);
  if (b.has_m && b.motion == Motion::None) {
    // An M code's words are its parameters, never a motion: M206 X40 Y40 sets a home offset
    // (seed 003, Tab. 2), M301 P.. I.. D.. PID gains. M codes are kept, not executed, so the
    // line changes nothing but the modal words it carries (docs/gcode.md "M lines").
    state_ = next;
    return out;
  }
  if (!b.has_axis()) {
    // A motion word alone (e.g. "G0 F1500", seed-003.md §2.2) only sets the mode.
    if (centre_words) return fail(ErrorKind::UnusedWord, first_column(b, {Word::I, Word::J}));
    state_ = next;
    return out;
  }
  if (next.motion == Motion::None) {
    return fail(ErrorKind::NoMotionMode, first_column(b, {Word::X, Word::Y, Word::Z}));
  }

  constexpr Word kAxes[3] = {Word::X, Word::Y, Word::Z};
  for (std::size_t k = 0; k < 3; ++k) {
    const Word w = kAxes[k];
    if (!b.has(w)) continue;
    const std::int64_t v = length_um(b.get(w), next.inches);
    const std::int64_t target = next.incremental ? state_.pos[k] + v : v;
    if (!in_range(target)) return fail(ErrorKind::PositionOutOfRange, b.col(w));
    m.to[k] = static_cast<std::int32_t>(target);
  }

  if (is_arc(next.motion)) {
    if (!centre_words) {
      const std::uint16_t col =
          b.motion_column != 0 ? b.motion_column : first_column(b, {Word::X, Word::Y, Word::Z});
      return fail(ErrorKind::ArcWithoutCentre, col);
    }
    // I and J are offsets from the arc start whatever G90/G91 says (grbl, LinuxCNC default;
    // the thesis's N05 "G02 Y100 I0 J-100", seed-003.md §2.5).
    const std::int64_t di = b.has(Word::I) ? length_um(b.get(Word::I), next.inches) : 0;
    const std::int64_t dj = b.has(Word::J) ? length_um(b.get(Word::J), next.inches) : 0;
    const std::int64_t cx = state_.pos[0] + di;
    const std::int64_t cy = state_.pos[1] + dj;
    if (!in_range(cx)) return fail(ErrorKind::PositionOutOfRange, b.col(Word::I));
    if (!in_range(cy)) return fail(ErrorKind::PositionOutOfRange, b.col(Word::J));
    if (di == 0 && dj == 0) return fail(ErrorKind::ArcZeroRadius, first_column(b, {Word::I, Word::J}));
    // |differences| <= 2e7 < 2^25, squares < 2^50, sums < 2^51: exact in 64 bits.
    const auto r2_start = static_cast<std::uint64_t>(square(di) + square(dj));
    const auto r2_end = static_cast<std::uint64_t>(square(m.to[0] - cx) + square(m.to[1] - cy));
    if (radius_mismatch(r2_start, r2_end)) {
      return fail(ErrorKind::ArcRadiusMismatch, first_column(b, {Word::X, Word::Y, Word::Z}));
    }
    m.kind = next.motion == Motion::ArcCw ? MoveKind::ArcCw : MoveKind::ArcCcw;
    m.centre_x = static_cast<std::int32_t>(cx);
    m.centre_y = static_cast<std::int32_t>(cy);
    m.feed_um_s = next.feed_um_s;
  } else {
    if (centre_words) return fail(ErrorKind::UnusedWord, first_column(b, {Word::I, Word::J}));
    m.kind = next.motion == Motion::Rapid ? MoveKind::Rapid : MoveKind::Linear;
    m.feed_um_s = next.motion == Motion::Rapid ? 0 : next.feed_um_s;
    m.z_only = m.from[0] == m.to[0] && m.from[1] == m.to[1];
  }

  next.pos = m.to;
  state_ = next;
  return out;
}

}  // namespace ap::xy_gcode
