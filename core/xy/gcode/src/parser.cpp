// G-code line parser (docs/gcode.md §Parser, seed-003.md §2.4 for the Thesis dialect).
#include "core/xy/gcode/parser.hpp"

#include <cstddef>
#include <cstdint>

namespace ap::xy_gcode {
namespace {

constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }
constexpr bool is_lower(char c) { return c >= 'a' && c <= 'z'; }
constexpr char to_upper(char c) { return is_lower(c) ? static_cast<char>(c - 'a' + 'A') : c; }

// Integer part limit: 99999 (so |value| <= 99999.9999, docs/gcode.md §Numbers).
constexpr std::int64_t kMaxIntegerPart = 99'999;
constexpr int kMaxFractionDigits = 4;

struct Number {
  ErrorKind error = ErrorKind::None;
  std::int32_t value = 0;  // 1e-4 units, |value| <= kMaxWordValue
  std::size_t end = 0;     // index just past the number
};

// [sign] digits* ['.' digits*], at least one digit; '+' only in Tolerant (the thesis writes
// none). The character after the number may not continue it ('.', '+', '-'): "1.2.3" is one
// bad number, not a number and a stray '.'.
Number parse_number(std::string_view s, std::size_t i, std::size_t end, Dialect d) {
  Number r;
  bool negative = false;
  if (i < end && (s[i] == '-' || s[i] == '+')) {
    if (s[i] == '+' && d == Dialect::Thesis) {
      r.error = ErrorKind::BadNumber;
      return r;
    }
    negative = s[i] == '-';
    ++i;
  }
  std::int64_t integer = 0;
  int digits = 0;
  bool too_big = false;
  while (i < end && is_digit(s[i])) {
    integer = integer * 10 + (s[i] - '0');
    if (integer > kMaxIntegerPart) {
      too_big = true;
      integer = kMaxIntegerPart + 1;  // keep the accumulator bounded; the number is rejected anyway
    }
    ++digits;
    ++i;
  }
  std::int64_t fraction = 0;
  int fraction_digits = 0;
  bool too_precise = false;
  if (i < end && s[i] == '.') {
    ++i;
    while (i < end && is_digit(s[i])) {
      if (fraction_digits >= kMaxFractionDigits) {  // keep counting, stop accumulating
        too_precise = true;
      } else {
        fraction = fraction * 10 + (s[i] - '0');
      }
      ++fraction_digits;
      ++i;
    }
  }
  if (digits + fraction_digits == 0) {
    r.error = ErrorKind::BadNumber;
  } else if (too_big) {
    r.error = ErrorKind::NumberOutOfRange;
  } else if (too_precise) {
    r.error = ErrorKind::TooManyDecimals;
  } else if (i < end && (s[i] == '.' || s[i] == '+' || s[i] == '-')) {
    r.error = ErrorKind::BadNumber;
  }
  if (r.error != ErrorKind::None) return r;
  for (int k = fraction_digits; k < kMaxFractionDigits; ++k) fraction *= 10;
  const std::int64_t magnitude = integer * kValueScale + fraction;  // <= 999 999 999
  r.value = static_cast<std::int32_t>(negative ? -magnitude : magnitude);
  r.end = i;
  return r;
}

struct Parser {
  std::string_view s;
  std::size_t end;  // one past the last byte that is parsed (a Tolerant final '\r' excluded)
  std::uint32_t line_no;
  Dialect dialect;
  Block block;
  int words = 0;  // words parsed so far (comments do not count)
  bool have_units = false;
  bool have_distance = false;
  std::size_t first_m_param = 0;  // 1 + index of the first S/P/D/E word, 0 if none

  ErrorKind fail_kind = ErrorKind::None;
  std::size_t fail_at = 0;

  bool fail(ErrorKind k, std::size_t at) {
    fail_kind = k;
    fail_at = at;
    return false;
  }

  static bool whole(std::int32_t v) { return v >= 0 && v % kValueScale == 0; }

  // One word whose letter is at index i; sets `next` to the index after its number.
  bool word(std::size_t i, std::size_t& next) {
    const char raw = s[i];
    if (!(is_upper(raw) || (dialect == Dialect::Tolerant && is_lower(raw)))) {
      return fail(ErrorKind::UnknownWord, i);
    }
    const char letter = to_upper(raw);
    const bool m_param = letter == 'S' || letter == 'P' || letter == 'D' || letter == 'E';
    const bool known = letter == 'N' || letter == 'G' || letter == 'M' || letter == 'X' || letter == 'Y' ||
                       letter == 'Z' || letter == 'I' || letter == 'J' || letter == 'F' || m_param;
    if (!known) return fail(ErrorKind::UnknownWord, i);
    const Number num = parse_number(s, i + 1, end, dialect);
    if (num.error != ErrorKind::None) return fail(num.error, i);
    next = num.end;
    const auto col = static_cast<std::uint16_t>(i + 1);
    switch (letter) {
      case 'N':
        if (words != 0) return fail(ErrorKind::MisplacedN, i);
        if (!whole(num.value)) return fail(ErrorKind::BadNumber, i);
        block.has_n = true;
        block.n = static_cast<std::uint32_t>(num.value / kValueScale);
        return true;
      case 'M':
        if (block.has_m) return fail(ErrorKind::DuplicateWord, i);
        if (!whole(num.value)) return fail(ErrorKind::BadNumber, i);
        block.has_m = true;
        block.m = static_cast<std::uint32_t>(num.value / kValueScale);
        return true;
      case 'G':
        return g_word(num.value, i, col);
      case 'S':
      case 'P':
      case 'D':
      case 'E': {
        // An M code's parameter: whether the line has its M word is only known at the end
        // of the line (finish()), where a stray one becomes UnknownWord at its column.
        const auto k = static_cast<std::uint8_t>(letter == 'S' ? 0 : letter == 'P' ? 1 : letter == 'D' ? 2 : 3);
        const auto bit = static_cast<std::uint8_t>(1U << k);
        if ((block.m_params & bit) != 0) return fail(ErrorKind::DuplicateWord, i);
        block.m_params = static_cast<std::uint8_t>(block.m_params | bit);
        block.m_value[k] = num.value;
        if (first_m_param == 0) first_m_param = i + 1;
        return true;
      }
      default:
        break;
    }
    Word w = Word::X;
    switch (letter) {
      case 'X': w = Word::X; break;
      case 'Y': w = Word::Y; break;
      case 'Z': w = Word::Z; break;
      case 'I': w = Word::I; break;
      case 'J': w = Word::J; break;
      default: w = Word::F; break;
    }
    if (block.has(w)) return fail(ErrorKind::DuplicateWord, i);
    block.present = static_cast<std::uint8_t>(block.present | Block::bit(w));
    block.value[static_cast<std::size_t>(w)] = num.value;
    block.column[static_cast<std::size_t>(w)] = col;
    return true;
  }

  // G words by modal group (LinuxCNC/grbl): one word per group per line.
  bool g_word(std::int32_t v, std::size_t i, std::uint16_t col) {
    if (!whole(v)) return fail(ErrorKind::UnsupportedG, i);
    const std::int32_t code = v / kValueScale;
    switch (code) {
      case 0:
      case 1:
      case 2:
      case 3:
        if (block.motion != Motion::None) return fail(ErrorKind::ModalGroupConflict, i);
        block.motion = static_cast<Motion>(code + 1);
        block.motion_column = col;
        return true;
      case 17:
        if (block.plane_xy) return fail(ErrorKind::ModalGroupConflict, i);
        block.plane_xy = true;
        return true;
      case 20:
      case 21:
        if (have_units) return fail(ErrorKind::ModalGroupConflict, i);
        have_units = true;
        block.units = code == 20 ? Units::Inch : Units::Millimetre;
        return true;
      case 90:
      case 91:
        if (have_distance) return fail(ErrorKind::ModalGroupConflict, i);
        have_distance = true;
        block.distance = code == 90 ? Distance::Absolute : Distance::Incremental;
        return true;
      default:
        return fail(ErrorKind::UnsupportedG, i);
    }
  }

  // Thesis (seed-003.md §2.4): "N<num>", then per further word exactly one space and the
  // word; the second word is G or M.
  bool thesis() {
    if (end == 0 || s[0] != 'N') return fail(ErrorKind::MissingN, 0);
    std::size_t i = 0;
    for (;;) {
      if (words == 1 && (i >= end || (s[i] != 'G' && s[i] != 'M'))) return fail(ErrorKind::MissingGorM, i);
      std::size_t next = 0;
      if (!word(i, next)) return false;
      ++words;
      if (next == end) {
        if (words == 1) return fail(ErrorKind::MissingGorM, end);
        return true;
      }
      if (s[next] != ' ') return fail(ErrorKind::BadSpacing, next);
      if (next + 1 == end) return fail(ErrorKind::BadSpacing, next);            // trailing space
      if (s[next + 1] == ' ') return fail(ErrorKind::BadSpacing, next + 1);     // double space
      i = next + 1;
    }
  }

  bool tolerant() {
    std::size_t i = 0;
    while (i < end) {
      const char c = s[i];
      if (c == ' ' || c == '\t') {
        ++i;
      } else if (c == '(') {
        std::size_t close = i + 1;
        while (close < end && s[close] != ')') ++close;
        if (close == end) return fail(ErrorKind::UnclosedComment, i);
        i = close + 1;
      } else if (c == ';') {
        return true;  // comment to end of line
      } else if (c == '%' && words == 0) {
        return true;  // program delimiter line (LinuxCNC, grbl): the rest is ignored
      } else {
        std::size_t next = 0;
        if (!word(i, next)) return false;
        ++words;
        i = next;
      }
    }
    return true;
  }

  bool characters() {
    for (std::size_t i = 0; i < end; ++i) {
      const auto b = static_cast<unsigned char>(s[i]);
      if (b == '\t') {
        if (dialect == Dialect::Thesis) return fail(ErrorKind::BadSpacing, i);
        continue;
      }
      if (b < 0x20 || b >= 0x7F) return fail(ErrorKind::BadCharacter, i);
    }
    return true;
  }
};

}  // namespace

ParseResult parse_line(std::string_view text, std::uint32_t line_no, Dialect d) {
  ParseResult out;
  out.block.line = line_no;
  out.error.line = line_no;
  if (text.size() > kMaxLineLength) {
    out.error.kind = ErrorKind::LineTooLong;
    out.error.column = static_cast<std::uint16_t>(kMaxLineLength + 1);
    return out;
  }
  std::size_t end = text.size();
  if (d == Dialect::Tolerant && end > 0 && text[end - 1] == '\r') --end;  // CRLF files
  Parser p{text, end, line_no, d, Block{}};
  p.block.line = line_no;
  bool ok = p.characters() && (d == Dialect::Thesis ? p.thesis() : p.tolerant());
  // S, P, D and E belong to an M code only (docs/gcode.md "M lines").
  if (ok && p.first_m_param != 0 && !p.block.has_m) ok = p.fail(ErrorKind::UnknownWord, p.first_m_param - 1);
  if (!ok) {
    out.error.kind = p.fail_kind;
    out.error.column = static_cast<std::uint16_t>(p.fail_at + 1);
    return out;
  }
  out.block = p.block;
  return out;
}

}  // namespace ap::xy_gcode
