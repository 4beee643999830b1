// G-code errors shared by the parser and the interpreter (docs/gcode.md §Errors).
// One enum for both stages so a caller reports any rejected line the same way: kind, line,
// 1-based column.
#pragma once

#include <cstdint>

namespace ap::xy_gcode {

enum class ErrorKind : std::uint8_t {
  None,
  // parser, any dialect
  LineTooLong,         // more than kMaxLineLength bytes
  BadCharacter,        // a control byte or a byte >= 0x7F (Tolerant: tab and a final '\r' are fine)
  UnknownWord,         // a character that cannot start a word (letter outside N G M X Y Z I J F, digit, ...)
  MisplacedN,          // an N word that is not the first word of the line
  BadNumber,           // no digits, "1.2.3", a sign where none may be, N or M not a whole number >= 0
  TooManyDecimals,     // more than 4 fraction digits
  NumberOutOfRange,    // magnitude above 99999.9999
  UnsupportedG,        // a G number other than 0 1 2 3 17 20 21 90 91 (G18, G19 included)
  ModalGroupConflict,  // two G words of the same modal group on one line
  DuplicateWord,       // X Y Z I J F or M twice on one line
  UnclosedComment,     // Tolerant: '(' without ')'
  // parser, Thesis dialect only (seed-003.md §2.4)
  MissingN,            // the line does not start with 'N' (the thesis's first error)
  MissingGorM,         // the second word is not G or M (the thesis's second error)
  BadSpacing,          // words not separated by exactly one space (leading/trailing/double space, tab)
  // interpreter
  NoMotionMode,        // axis words but no G0/G1/G2/G3 set so far
  PositionOutOfRange,  // a target or arc centre beyond +-kMaxPositionUm
  ArcWithoutCentre,    // G2/G3 move with neither I nor J (the R form is not supported)
  ArcZeroRadius,       // I = J = 0 after conversion to um
  ArcRadiusMismatch,   // start and end radius differ beyond grbl's tolerance
  UnusedWord,          // I or J on a line that is not an arc move
  BadFeed,             // F <= 0, or an F so small it rounds to 0 um/s
};

inline constexpr int kErrorKindCount = static_cast<int>(ErrorKind::BadFeed) + 1;

// column: 1-based column of the offending character, or of the letter of the offending word;
// length + 1 when the line ends too early. 0 only with kind == None.
struct Error {
  ErrorKind kind = ErrorKind::None;
  std::uint32_t line = 0;
  std::uint16_t column = 0;

  constexpr bool ok() const { return kind == ErrorKind::None; }
  bool operator==(const Error&) const = default;
};

// The enumerator's name ("MissingN"), or "?" for a value outside the enum.
const char* error_name(ErrorKind kind);

}  // namespace ap::xy_gcode
