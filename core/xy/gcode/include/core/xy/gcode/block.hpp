// One parsed G-code line (docs/gcode.md §Block). Numbers are kept exactly as written, as
// integers in units of 1e-4 of the line's length unit (mm or inch; F per minute): the
// interpreter, which knows G20/G21, converts them. No floating point (house rule).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace ap::xy_gcode {

// Largest magnitude of a number word: 99999.9999 -> 999 999 999 in 1e-4 units (< 2^31).
inline constexpr std::int32_t kMaxWordValue = 999'999'999;
// Scale of a stored value: 1.0 is stored as 10 000.
inline constexpr std::int32_t kValueScale = 10'000;
// Largest N and M number (whole numbers; the integer part of a number is at most 99999).
inline constexpr std::uint32_t kMaxCode = 99'999;

// Modal group 1 (motion). Also the interpreter's motion mode.
enum class Motion : std::uint8_t { None, Rapid /*G0*/, Linear /*G1*/, ArcCw /*G2*/, ArcCcw /*G3*/ };
// Modal group 6 (units), as written on the line.
enum class Units : std::uint8_t { Unchanged, Millimetre /*G21*/, Inch /*G20*/ };
// Modal group 3 (distance mode), as written on the line.
enum class Distance : std::uint8_t { Unchanged, Absolute /*G90*/, Incremental /*G91*/ };

// The value words, in this order in Block::value / Block::column.
enum class Word : std::uint8_t { X, Y, Z, I, J, F };
inline constexpr std::size_t kWordCount = 6;

// Parameter words that only an M code takes (M106 S127, M301 P.. I.. D.., M204 P.., M221 S..,
// M92 E..; docs/gcode.md "M lines"). On a line without an M word they are UnknownWord.
enum class MParam : std::uint8_t { S, P, D, E };
inline constexpr std::size_t kMParamCount = 4;

struct Block {
  // What the line says. Absent words hold 0.
  bool has_n = false;
  std::uint32_t n = 0;                         // 0..kMaxCode
  bool has_m = false;
  std::uint32_t m = 0;                         // 0..kMaxCode, kept, never executed (seed-003.md §2.4)
  std::uint8_t m_params = 0;                   // bit (1 << MParam) set: that M parameter word is on the line
  std::array<std::int32_t, kMParamCount> m_value{};  // |v| <= kMaxWordValue, 1e-4 units
  Motion motion = Motion::None;                // G0..G3 on this line, None if absent
  bool plane_xy = false;                       // G17 on this line
  Units units = Units::Unchanged;
  Distance distance = Distance::Unchanged;
  std::uint8_t present = 0;                    // bit (1 << Word) set: that word is on the line
  std::array<std::int32_t, kWordCount> value{};  // |v| <= kMaxWordValue, 1e-4 units

  // Where it says it (for the interpreter's error reports); not part of operator==.
  std::uint32_t line = 0;
  std::uint16_t motion_column = 0;             // column of the G0..G3 word, 0 if absent
  std::array<std::uint16_t, kWordCount> column{};  // column of each present word's letter

  constexpr bool has(Word w) const { return (present & bit(w)) != 0; }
  constexpr std::int32_t get(Word w) const { return value[static_cast<std::size_t>(w)]; }
  constexpr std::uint16_t col(Word w) const { return column[static_cast<std::size_t>(w)]; }
  constexpr bool has_axis() const { return (present & (bit(Word::X) | bit(Word::Y) | bit(Word::Z))) != 0; }
  static constexpr std::uint8_t bit(Word w) { return static_cast<std::uint8_t>(1U << static_cast<unsigned>(w)); }

  // Same content: source positions (line, columns) are ignored, so a block formatted and
  // parsed back compares equal (the round-trip property, properties/xy/gcode).
  friend constexpr bool operator==(const Block& a, const Block& b) {
    return a.has_n == b.has_n && a.n == b.n && a.has_m == b.has_m && a.m == b.m && a.motion == b.motion &&
           a.plane_xy == b.plane_xy && a.units == b.units && a.distance == b.distance && a.present == b.present &&
           a.value == b.value && a.m_params == b.m_params && a.m_value == b.m_value;
  }
};

}  // namespace ap::xy_gcode
