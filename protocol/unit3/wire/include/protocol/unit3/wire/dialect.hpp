#pragma once
// The 3-axis USB unit's `;` dialect (seed 001 §2, decisions in docs/unit3.md "The wire").
// PC -> unit, one ASCII command per `;`:
//   D<s><s><s>;        direction of X, Y, Z for the next moves, s = '+' or '-'
//   X|Y|Z<15 digits>;  relative move of one axis by that many 1/32-step counts
//   M<d><d><d>;        step mode of X, Y, Z: d = 0..5, step 1/2^d (DRV8825 MODE2..0)
//   T<d><d><d>;        thread of X, Y, Z: d = 0..6, an index into the pitch table
//   C;                 zero the three step counters
//   G;                 send the stored settings
// Unit -> PC: X|Y|Z<sign><18 digits>; (a step counter), M<d><d><d>; and T<d><d><d>; (settings),
// E<2 digits>; (a command refused: the line's Error, or the unit's reason, docs/unit3.md).
// Every command has one fixed length, so a byte lost on the 19200-baud line always leaves a
// line of the wrong length or shape: it is rejected with a typed error and runs nothing.
// Heap-free and integer-only: the unit's firmware parses with it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace ap::unit3_wire {

inline constexpr std::size_t kAxes = 3;
enum class Axis : std::uint8_t { X = 0, Y = 1, Z = 2 };

inline constexpr char kEnd = ';';
inline constexpr std::size_t kCountDigits = 15;       // the move's field (seed 001 §2.3)
inline constexpr std::size_t kMaxLine = 1 + kCountDigits + 1;  // the longest command, with ';'
inline constexpr std::uint64_t kMaxCount = 999'999'999'999'999ULL;  // 15 nines
inline constexpr std::uint8_t kMaxModeDigit = 5;      // 1/32 step
inline constexpr std::uint8_t kMaxThreadDigit = 6;    // M10
inline constexpr std::size_t kReportDigits = 18;      // |counter| <= 10^18 - 1 (docs/unit3.md)
inline constexpr std::int64_t kMaxReportCount = 999'999'999'999'999'999LL;
inline constexpr std::size_t kReportLength = 1 + 1 + kReportDigits + 1;

enum class Kind : std::uint8_t { Direction, Move, StepMode, Thread, Clear, Get };

struct Command {
  Kind kind = Kind::Clear;
  Axis axis = Axis::X;                  // Move
  std::uint64_t count = 0;              // Move: 1/32-step counts, 0 .. kMaxCount
  std::array<std::int8_t, kAxes> sign{};    // Direction: +1 or -1 per axis
  std::array<std::uint8_t, kAxes> digit{};  // StepMode 0..5, Thread 0..6 per axis
  friend constexpr bool operator==(const Command&, const Command&) = default;
};

// Why a line was rejected; the offset names the first byte at fault (from the line's start).
enum class Error : std::uint8_t {
  None = 0,
  UnknownCommand,   // first byte is none of D X Y Z M T C G (lower case included)
  BadLength,        // `;` too early or too late for this command (a lost or extra byte)
  BadDigit,         // not a decimal digit where one is due
  BadSign,          // not '+' or '-' in a D command
  ModeOutOfRange,   // M digit 6..9
  ThreadOutOfRange, // T digit 7..9
  TooLong,          // no `;` within kMaxLine bytes: the line is dropped up to the next `;`
};

struct Rejection {
  Error error = Error::None;
  std::uint8_t offset = 0;
  constexpr bool ok() const { return error == Error::None; }
  friend constexpr bool operator==(const Rejection&, const Rejection&) = default;
};

const char* error_key(Error e);

// One line, its `;` included. On error `out` is untouched.
Rejection parse(std::span<const std::uint8_t> line, Command& out);

// Writes the command's line (`;` included) and returns its length; 0, writing nothing, when
// a field is out of range (count > kMaxCount, a sign not +-1, a digit past its table).
std::size_t format(const Command& c, std::span<std::uint8_t, kMaxLine> out);

// The unit's counter report, e.g. X+000000000000016000; (kReportLength bytes); 0 when
// |count| > kMaxReportCount.
std::size_t format_report(Axis a, std::int64_t count, std::span<std::uint8_t, kReportLength> out);
// Reads a counter report back (the PC side and the tests); nullopt on any deviation.
struct Report {
  Axis axis = Axis::X;
  std::int64_t count = 0;
  friend constexpr bool operator==(const Report&, const Report&) = default;
};
std::optional<Report> parse_report(std::span<const std::uint8_t> line);

// The unit's refusal of a command, E<2 digits>; (kErrorLength bytes). Codes 01..07 are the
// line's Error; the unit's own reasons start at kFirstUnitCode (docs/unit3.md "Replies").
inline constexpr std::size_t kErrorLength = 4;
inline constexpr std::uint8_t kFirstUnitCode = 20;
// 0 when code is 0 or above 99.
std::size_t format_error(std::uint8_t code, std::span<std::uint8_t, kErrorLength> out);
std::optional<std::uint8_t> parse_error(std::span<const std::uint8_t> line);

// Bytes in any chunks -> lines. CR, LF, space and tab between commands are skipped (a PC
// terminal's line ends); inside a command they are bytes like any other. A line without `;`
// within kMaxLine bytes is rejected once (TooLong) and the bytes up to the next `;` dropped.
class Framer {
 public:
  struct Event {
    Command command{};
    Rejection rejection{};
    std::uint32_t stream_offset = 0;  // of the line's first byte
  };
  struct Counters {
    std::uint32_t accepted = 0;
    std::uint32_t rejected = 0;
    friend constexpr bool operator==(const Counters&, const Counters&) = default;
  };

  std::optional<Event> push(std::uint8_t b);
  template <class Sink>
  void feed(std::span<const std::uint8_t> bytes, Sink&& sink) {
    for (const std::uint8_t b : bytes) {
      if (auto e = push(b)) sink(*e);
    }
  }
  std::size_t pending() const { return len_ + (dropping_ ? 1 : 0); }
  Counters counters() const { return counters_; }

 private:
  std::array<std::uint8_t, kMaxLine> buf_{};
  std::size_t len_ = 0;
  bool dropping_ = false;
  std::uint32_t offset_ = 0;  // stream position of the next byte
  std::uint32_t start_ = 0;   // of the current line
  Counters counters_{};
};

}  // namespace ap::unit3_wire
