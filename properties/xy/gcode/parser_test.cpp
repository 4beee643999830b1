// G-code parser: the thesis program (seed-003.md §2.5) in both dialects, every error kind at
// its exact column (docs/gcode.md §Errors), the Thesis-vs-Tolerant differences
// (seed-003.md §2.4), and the format -> parse round trip as a property.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/xy/gcode/parser.hpp"
#include "thesis_program.hpp"

namespace {

using namespace ap::xy_gcode;

Block parse_ok(const std::string& s, Dialect d) {
  const auto r = parse_line(s, 1, d);
  EXPECT_EQ(r.error.kind, ErrorKind::None) << '"' << s << "\" -> " << error_name(r.error.kind) << " at column "
                                           << r.error.column;
  return r.block;
}

struct Case {
  const char* text;
  Dialect dialect;
  ErrorKind kind;
  std::uint16_t column;
};

void expect_errors(const std::vector<Case>& cases) {
  for (const auto& c : cases) {
    const auto r = parse_line(c.text, 7, c.dialect);
    EXPECT_EQ(error_name(r.error.kind), std::string(error_name(c.kind)))
        << '"' << c.text << "\" (" << (c.dialect == Dialect::Thesis ? "Thesis" : "Tolerant") << ")";
    EXPECT_EQ(r.error.column, c.column) << '"' << c.text << '"';
    EXPECT_EQ(r.error.line, 7U);
    EXPECT_EQ(r.block, Block{}) << "a rejected line yields an empty block";
  }
}

constexpr Dialect T = Dialect::Thesis;
constexpr Dialect L = Dialect::Tolerant;

// ---- the thesis program -----------------------------------------------------------------

TEST(GcodeThesisProgram, ParsesInBothDialectsToTheSameBlocks) {
  const auto lines = gcode_test::thesis_lines();
  ASSERT_EQ(lines.size(), 8U);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto t = parse_line(lines[i], static_cast<std::uint32_t>(i + 1), T);
    const auto l = parse_line(lines[i], static_cast<std::uint32_t>(i + 1), L);
    EXPECT_TRUE(t.error.ok()) << lines[i] << ": " << error_name(t.error.kind);
    EXPECT_TRUE(l.error.ok()) << lines[i] << ": " << error_name(l.error.kind);
    EXPECT_EQ(t.block, l.block) << lines[i];
    EXPECT_EQ(t.block.line, i + 1);
    EXPECT_TRUE(t.block.has_n);
    EXPECT_EQ(t.block.n, i + 1) << "N01..N08";
  }
}

TEST(GcodeThesisProgram, WordsOfN05) {
  // "N05 G02 Y100 I0 J-100": values in 1e-4 mm.
  const Block b = parse_ok("N05 G02 Y100 I0 J-100", T);
  EXPECT_EQ(b.motion, Motion::ArcCw);
  EXPECT_EQ(b.present, Block::bit(Word::Y) | Block::bit(Word::I) | Block::bit(Word::J));
  EXPECT_EQ(b.get(Word::Y), 1'000'000);
  EXPECT_EQ(b.get(Word::I), 0);
  EXPECT_EQ(b.get(Word::J), -1'000'000);
  EXPECT_EQ(b.col(Word::Y), 9);
  EXPECT_EQ(b.col(Word::I), 14);
  EXPECT_EQ(b.col(Word::J), 17);
  EXPECT_EQ(b.motion_column, 5);
}

TEST(GcodeThesisProgram, WordsOfN02) {
  const Block b = parse_ok("N02 G01 Z0 F2000", T);
  EXPECT_EQ(b.motion, Motion::Linear);
  EXPECT_EQ(b.get(Word::Z), 0);
  EXPECT_TRUE(b.has(Word::Z));
  EXPECT_EQ(b.get(Word::F), 20'000'000);
  EXPECT_FALSE(b.has(Word::X));
}

// ---- G01 == G1 and number forms ----------------------------------------------------------

TEST(GcodeParser, LeadingZerosInGCodesAreTheSameCode) {
  for (const Dialect d : {T, L}) {
    EXPECT_EQ(parse_ok("N1 G01 X1", d), parse_ok("N1 G1 X1", d));
    EXPECT_EQ(parse_ok("N1 G00 X1", d), parse_ok("N1 G0 X1", d));
    EXPECT_EQ(parse_ok("N1 G0002 Y1", d), parse_ok("N1 G2 Y1", d));
    EXPECT_EQ(parse_ok("N001 M03", d).m, 3U);
    EXPECT_EQ(parse_ok("N1 G1", d).motion, Motion::Linear);  // a G word alone (seed-003.md §2.4)
  }
}

TEST(GcodeParser, NumberForms) {
  EXPECT_EQ(parse_ok("G1 X1.5", L).get(Word::X), 15'000);
  EXPECT_EQ(parse_ok("G1 X.5", L).get(Word::X), 5'000);
  EXPECT_EQ(parse_ok("G1 X5.", L).get(Word::X), 50'000);
  EXPECT_EQ(parse_ok("G1 X-0.0001", L).get(Word::X), -1);
  EXPECT_EQ(parse_ok("G1 X+2.25", L).get(Word::X), 22'500);
  EXPECT_EQ(parse_ok("G1 X-0", L).get(Word::X), 0);
  EXPECT_EQ(parse_ok("G1 X99999.9999", L).get(Word::X), 999'999'999);
  EXPECT_EQ(parse_ok("G1 X-99999.9999", L).get(Word::X), -999'999'999);
  EXPECT_EQ(parse_ok("G1 X0000099999", L).get(Word::X), 999'990'000);  // leading zeros are not digits of range
  EXPECT_EQ(parse_ok("N01 G01 Y-0.1234", T).get(Word::Y), -1'234);
}

TEST(GcodeParser, TolerantForms) {
  const Block canonical = parse_ok("N10 G1 X1 Y2 F300", T);
  for (const char* s : {"N10 G1 X1 Y2 F300", "n10 g1 x1 y2 f300", "N10G1X1Y2F300", "  N10\tG1   X1 Y2 F300  ",
                        "N10 G1 X1 (move) Y2 F300 ; comment", "N10 G1 X1 Y2 F300\r", "N10 (a) G1 (b) X1Y2(c)F300",
                        "N10 G1 X+1 Y+2.000 F300.0"}) {
    EXPECT_EQ(parse_ok(s, L), canonical) << s;
  }
  EXPECT_EQ(parse_ok("G90 G1 X1", L).distance, Distance::Absolute);
  EXPECT_EQ(parse_ok("G90 G1 X1", L).motion, Motion::Linear);
  const Block all = parse_ok("G17 G21 G91 G3 X1 I1", L);
  EXPECT_TRUE(all.plane_xy);
  EXPECT_EQ(all.units, Units::Millimetre);
  EXPECT_EQ(all.distance, Distance::Incremental);
  EXPECT_EQ(all.motion, Motion::ArcCcw);
  EXPECT_EQ(parse_ok("G20", L).units, Units::Inch);
  // Blank, comment-only and '%' lines are empty blocks.
  for (const char* s : {"", "   ", "\t", "(only a comment)", "; only a comment", "%", "% program 1", "\r"}) {
    EXPECT_EQ(parse_ok(s, L), Block{}) << '"' << s << '"';
  }
  EXPECT_EQ(parse_ok("N5", L).n, 5U);
}

// ---- strict vs tolerant ------------------------------------------------------------------

TEST(GcodeDialect, ThesisRejectsWhatTolerantAccepts) {
  struct Diff {
    const char* text;
    ErrorKind thesis_kind;
    std::uint16_t column;
  };
  const Block canonical = parse_ok("N01 G01 X200 Y200", T);
  for (const Diff& d : std::vector<Diff>{
           {"N01  G01 X200 Y200", ErrorKind::BadSpacing, 5},       // double space
           {"N01 G01 X200  Y200", ErrorKind::BadSpacing, 14},
           {"N01\tG01 X200 Y200", ErrorKind::BadSpacing, 4},       // tab
           {"N01 G01 X200 Y200 ", ErrorKind::BadSpacing, 18},      // trailing space
           {" N01 G01 X200 Y200", ErrorKind::MissingN, 1},         // leading space
           {"n01 G01 X200 Y200", ErrorKind::MissingN, 1},          // lowercase
           {"N01 g01 X200 Y200", ErrorKind::MissingGorM, 5},
           {"N01 G01 x200 Y200", ErrorKind::UnknownWord, 9},
           {"N01 G01 X200 Y200 (comment)", ErrorKind::UnknownWord, 19},
           {"N01 G01 X200 Y200 ;comment", ErrorKind::UnknownWord, 19},
           {"G01 X200 Y200", ErrorKind::MissingN, 1},              // missing N
           {"N01 G01 X+200 Y200", ErrorKind::BadNumber, 9},        // '+' sign
           {"N01 G01 X200Y200", ErrorKind::BadSpacing, 13},        // no space
           {"N01 G01 X200 Y200\r", ErrorKind::BadCharacter, 18},   // CRLF
       }) {
    const auto t = parse_line(d.text, 3, T);
    EXPECT_EQ(error_name(t.error.kind), std::string(error_name(d.thesis_kind))) << d.text;
    EXPECT_EQ(t.error.column, d.column) << d.text;
    Block want = canonical;
    if (d.text[0] == 'G') {  // the missing-N case: Tolerant takes it, without a line number
      want.has_n = false;
      want.n = 0;
    }
    EXPECT_EQ(parse_ok(d.text, L), want) << d.text;
  }
}

// An M code takes its own parameter words (Marlin/RepRap usage the study's Tab. 2 points at:
// M106 S127 fan speed, M301 P I D gains, M204 P, M92 E); without an M word on the line they
// are not words of ours (docs/gcode.md "M lines").
TEST(GcodeParser, MParameterWordsBelongToTheMCode) {
  for (const Dialect d : {T, L}) {
    const Block fan = parse_ok("N1 M106 S127", d);
    EXPECT_EQ(fan.m, 106U);
    EXPECT_EQ(fan.m_params, 1U << static_cast<unsigned>(MParam::S));
    EXPECT_EQ(fan.m_value[static_cast<std::size_t>(MParam::S)], 1'270'000);
    const Block pid = parse_ok("N2 M301 P22.2 I1.08 D114", d);
    EXPECT_EQ(pid.m_value[static_cast<std::size_t>(MParam::P)], 222'000);
    EXPECT_EQ(pid.m_value[static_cast<std::size_t>(MParam::D)], 1'140'000);
    EXPECT_EQ(pid.get(Word::I), 10'800);
    EXPECT_EQ(parse_ok("N3 M92 E93", d).m_value[static_cast<std::size_t>(MParam::E)], 930'000);
    EXPECT_EQ(parse_ok("N4 M3 S1000", d).m_value[static_cast<std::size_t>(MParam::S)], 10'000'000);
  }
  expect_errors({{"N1 G1 X2 S100", T, ErrorKind::UnknownWord, 10},
                 {"G1 X2 P5", L, ErrorKind::UnknownWord, 7},
                 {"M106 S1 S2", L, ErrorKind::DuplicateWord, 9}});
}

TEST(GcodeDialect, ThesisAcceptsOnlyGOrMAsSecondWord) {
  EXPECT_EQ(parse_ok("N01 M106", T).m, 106U);
  EXPECT_TRUE(parse_ok("N01 M106", T).has_m);
  EXPECT_EQ(parse_ok("N01 G01 M3", T).m, 3U);  // M after G is a further word
  expect_errors({{"N01 X200", T, ErrorKind::MissingGorM, 5}, {"N01 F100", T, ErrorKind::MissingGorM, 5}});
}

// ---- every error kind, several cases each, exact columns --------------------------------

TEST(GcodeParserErrors, LineTooLong) {
  const std::string ok256(256, ' ');
  EXPECT_EQ(parse_ok(ok256, L), Block{});
  const std::string longer = "N1 G1 X1" + std::string(249, ' ');  // 257 bytes
  expect_errors({{longer.c_str(), L, ErrorKind::LineTooLong, 257},
                 {longer.c_str(), T, ErrorKind::LineTooLong, 257}});
  const std::string huge(5000, 'X');
  expect_errors({{huge.c_str(), L, ErrorKind::LineTooLong, 257}});
}

TEST(GcodeParserErrors, BadCharacter) {
  expect_errors({
      {"N1 G1 X1\x01", L, ErrorKind::BadCharacter, 9},
      {"N1 G1 X1\x01", T, ErrorKind::BadCharacter, 9},
      {"G1 X\xC3\xA9", L, ErrorKind::BadCharacter, 5},
      {"G1 (\xC3\xA9)", L, ErrorKind::BadCharacter, 5},  // no bytes >= 0x80, not even in comments
      {"G1\rX1", L, ErrorKind::BadCharacter, 3},          // '\r' only as the last byte
      {"N01 G01 X1\r", T, ErrorKind::BadCharacter, 11},
      {"G1 X1\x7F", L, ErrorKind::BadCharacter, 6},
      {"  G1  X1 \x1B", L, ErrorKind::BadCharacter, 10},
  });
  // a NUL byte inside the line
  const std::string nul("G1 X\0" "1", 6);
  const auto r = parse_line(nul, 1, L);
  EXPECT_EQ(r.error.kind, ErrorKind::BadCharacter);
  EXPECT_EQ(r.error.column, 5);
}

TEST(GcodeParserErrors, UnknownWord) {
  expect_errors({
      {"N01 G01 E5", T, ErrorKind::UnknownWord, 9},
      {"G1 X1 E0.5", L, ErrorKind::UnknownWord, 7},  // Marlin's extruder word (seed-003.md §2.2)
      {"G2 X10 R5", L, ErrorKind::UnknownWord, 8},   // the R form of arcs is not supported
      {"G1 X1 *57", L, ErrorKind::UnknownWord, 7},   // Marlin checksum
      {"#1=5", L, ErrorKind::UnknownWord, 1},
      {"G1 X1 5", L, ErrorKind::UnknownWord, 7},
      {"G1 X1 S1000", L, ErrorKind::UnknownWord, 7},  // S belongs to an M code only
      {"N01 G01 X1 %", T, ErrorKind::UnknownWord, 12},
      {"G1 X1 %", L, ErrorKind::UnknownWord, 7},     // '%' only as the first thing on a line
  });
}

TEST(GcodeParserErrors, MisplacedN) {
  expect_errors({
      {"G1 N5 X1", L, ErrorKind::MisplacedN, 4},
      {"N01 G01 N02", T, ErrorKind::MisplacedN, 9},
      {"N1 N2", L, ErrorKind::MisplacedN, 4},
      {"(c) X1 n3", L, ErrorKind::MisplacedN, 8},
  });
}

TEST(GcodeParserErrors, BadNumber) {
  expect_errors({
      {"G1 X", L, ErrorKind::BadNumber, 4},
      {"G1 X-", L, ErrorKind::BadNumber, 4},
      {"G1 X.", L, ErrorKind::BadNumber, 4},
      {"G1 X Y1", L, ErrorKind::BadNumber, 4},
      {"G1 X1.2.3", L, ErrorKind::BadNumber, 4},
      {"G1 X1-2", L, ErrorKind::BadNumber, 4},
      {"N1.5 G1", L, ErrorKind::BadNumber, 1},
      {"N-1 G1", L, ErrorKind::BadNumber, 1},
      {"M-3", L, ErrorKind::BadNumber, 1},
      {"M3.5", L, ErrorKind::BadNumber, 1},
      {"N G1", T, ErrorKind::BadNumber, 1},
      {"N01 G01 X+5", T, ErrorKind::BadNumber, 9},
      {"N01 G", T, ErrorKind::BadNumber, 5},
  });
}

TEST(GcodeParserErrors, TooManyDecimals) {
  EXPECT_EQ(parse_ok("G1 X1.2345", L).get(Word::X), 12'345);
  expect_errors({
      {"G1 X1.00001", L, ErrorKind::TooManyDecimals, 4},
      {"N01 G01 Y-0.12345", T, ErrorKind::TooManyDecimals, 9},
      {"G1 F.000001", L, ErrorKind::TooManyDecimals, 4},
      {"G1 X1 Y2 Z3.141592", L, ErrorKind::TooManyDecimals, 10},
      // 25 fraction digits: the digits past the 4th are counted, never accumulated (a fuzz
      // finding, fuzz/regressions/gcode_parser/fraction-accumulator-overflow).
      {"G1 X1.2222222222222222222222222", L, ErrorKind::TooManyDecimals, 4},
  });
}

TEST(GcodeParserErrors, NumberOutOfRange) {
  expect_errors({
      {"G1 X100000", L, ErrorKind::NumberOutOfRange, 4},
      {"G1 X-100000.0", L, ErrorKind::NumberOutOfRange, 4},
      {"G1 F123456", L, ErrorKind::NumberOutOfRange, 4},
      {"N100000 G1", L, ErrorKind::NumberOutOfRange, 1},
      {"N01 G01 X99999999999999999999999", T, ErrorKind::NumberOutOfRange, 9},
      {"G1 X100000.12345", L, ErrorKind::NumberOutOfRange, 4},  // integer part is checked first
  });
}

TEST(GcodeParserErrors, UnsupportedG) {
  expect_errors({
      {"G18", L, ErrorKind::UnsupportedG, 1},
      {"G19 G2 X1 I1", L, ErrorKind::UnsupportedG, 1},
      {"N01 G04 X1", T, ErrorKind::UnsupportedG, 5},
      {"N01 G28", T, ErrorKind::UnsupportedG, 5},
      {"G1 G38.2 X1", L, ErrorKind::UnsupportedG, 4},
      {"G1.5", L, ErrorKind::UnsupportedG, 1},
      {"G-1", L, ErrorKind::UnsupportedG, 1},
      {"G92 X0", L, ErrorKind::UnsupportedG, 1},
  });
}

TEST(GcodeParserErrors, ModalGroupConflict) {
  expect_errors({
      {"G0 G1 X1", L, ErrorKind::ModalGroupConflict, 4},
      {"G20 G21", L, ErrorKind::ModalGroupConflict, 5},
      {"G90 X1 G91", L, ErrorKind::ModalGroupConflict, 8},
      {"G17 G17", L, ErrorKind::ModalGroupConflict, 5},
      {"N01 G01 G02 X1", T, ErrorKind::ModalGroupConflict, 9},
      {"G1 G1 X1", L, ErrorKind::ModalGroupConflict, 4},
  });
}

TEST(GcodeParserErrors, DuplicateWord) {
  expect_errors({
      {"G1 X1 X2", L, ErrorKind::DuplicateWord, 7},
      {"N01 G01 X1 Y2 Y3", T, ErrorKind::DuplicateWord, 15},
      {"M3 M5", L, ErrorKind::DuplicateWord, 4},
      {"G1 F1 F2", L, ErrorKind::DuplicateWord, 7},
      {"G2 X1 I1 J1 i1", L, ErrorKind::DuplicateWord, 13},
  });
}

TEST(GcodeParserErrors, UnclosedComment) {
  expect_errors({
      {"G1 X1 (abc", L, ErrorKind::UnclosedComment, 7},
      {"(", L, ErrorKind::UnclosedComment, 1},
      {"G1 (a) X1 (b", L, ErrorKind::UnclosedComment, 11},
  });
}

TEST(GcodeParserErrors, MissingN) {
  expect_errors({
      {"G01 X1", T, ErrorKind::MissingN, 1},
      {"", T, ErrorKind::MissingN, 1},
      {"n01 G01", T, ErrorKind::MissingN, 1},
      {" N01 G01", T, ErrorKind::MissingN, 1},
      {"%", T, ErrorKind::MissingN, 1},
  });
}

TEST(GcodeParserErrors, MissingGorM) {
  expect_errors({
      {"N01 X200", T, ErrorKind::MissingGorM, 5},
      {"N01", T, ErrorKind::MissingGorM, 4},  // the line ends where G or M should be
      {"N01 g01", T, ErrorKind::MissingGorM, 5},
      {"N1234 (c)", T, ErrorKind::MissingGorM, 7},
  });
}

TEST(GcodeParserErrors, BadSpacing) {
  expect_errors({
      {"N01  G01", T, ErrorKind::BadSpacing, 5},
      {"N01 G01 ", T, ErrorKind::BadSpacing, 8},
      {"N01\tG01", T, ErrorKind::BadSpacing, 4},
      {"N01G01", T, ErrorKind::BadSpacing, 4},
      {"N01 G01 X1Y2", T, ErrorKind::BadSpacing, 11},
      {"N01 ", T, ErrorKind::BadSpacing, 4},
  });
}

TEST(GcodeParserErrors, EveryParserKindIsNamed) {
  for (int k = 0; k < kErrorKindCount; ++k) {
    EXPECT_NE(std::string(error_name(static_cast<ErrorKind>(k))), "?") << k;
  }
  EXPECT_EQ(std::string(error_name(ErrorKind::MissingN)), "MissingN");
  EXPECT_EQ(std::string(error_name(static_cast<ErrorKind>(200))), "?");
}

// ---- round trip: format(Block) -> parse -> same Block -----------------------------------

// A small independent formatter: value v (1e-4 units) as "[-]int[.frac]", with the
// fraction's trailing zeros dropped or kept and optional leading zeros (G01 style).
std::string number(std::int32_t v, bool keep_zeros, int leading_zeros) {
  std::string s = v < 0 ? "-" : "";
  const std::int64_t a = v < 0 ? -static_cast<std::int64_t>(v) : v;
  s += std::string(static_cast<std::size_t>(leading_zeros), '0') + std::to_string(a / 10000);
  std::string frac = std::to_string(a % 10000);
  frac = std::string(4 - frac.size(), '0') + frac;
  if (!keep_zeros) {
    while (!frac.empty() && frac.back() == '0') frac.pop_back();
  }
  if (!frac.empty()) s += "." + frac;
  return s;
}

struct Formatting {
  bool thesis;              // "N.. G..|M.." then words, single spaces, uppercase
  std::vector<int> seps;    // Tolerant: separator style per word
  bool lower;
  bool keep_zeros;
  int leading;
};

std::string format(const Block& b, const Formatting& f) {
  std::vector<std::string> words;
  if (b.has_n) words.push_back("N" + number(static_cast<std::int32_t>(b.n) * 10000, false, f.leading));
  if (b.motion != Motion::None) words.push_back("G" + std::to_string(static_cast<int>(b.motion) - 1));
  if (b.has_m) words.push_back("M" + std::to_string(b.m));
  if (b.plane_xy) words.push_back("G17");
  if (b.units != Units::Unchanged) words.push_back(b.units == Units::Inch ? "G20" : "G21");
  if (b.distance != Distance::Unchanged) words.push_back(b.distance == Distance::Absolute ? "G90" : "G91");
  const char letters[kWordCount] = {'X', 'Y', 'Z', 'I', 'J', 'F'};
  for (std::size_t w = 0; w < kWordCount; ++w) {
    if (b.present & (1U << w)) words.push_back(letters[w] + number(b.value[w], f.keep_zeros, f.leading));
  }
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) {
    std::string w = words[i];
    if (f.lower) {
      for (auto& c : w) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    if (f.thesis) {
      out += (i == 0 ? "" : " ") + w;
    } else {
      static const char* const kSeps[] = {"", " ", "\t", "  ", " (c) ", "(x)"};
      out += kSeps[f.seps[i % f.seps.size()] % 6] + w;
    }
  }
  if (!f.thesis && !f.seps.empty() && f.seps[0] % 2 == 1) out += " ; tail";
  return out;
}

Block gen_block(bool thesis) {
  Block b;
  b.has_n = thesis || *rc::gen::arbitrary<bool>();
  if (b.has_n) b.n = *rc::gen::inRange<std::uint32_t>(0, kMaxCode + 1);
  b.motion = static_cast<Motion>(*rc::gen::inRange(0, 5));
  b.has_m = *rc::gen::arbitrary<bool>();
  if (thesis && b.motion == Motion::None) b.has_m = true;  // second word must be G or M
  if (b.has_m) b.m = *rc::gen::inRange<std::uint32_t>(0, kMaxCode + 1);
  b.plane_xy = *rc::gen::arbitrary<bool>();
  b.units = static_cast<Units>(*rc::gen::inRange(0, 3));
  b.distance = static_cast<Distance>(*rc::gen::inRange(0, 3));
  b.present = *rc::gen::inRange<std::uint8_t>(0, 64);
  for (std::size_t w = 0; w < kWordCount; ++w) {
    if (b.present & (1U << w)) {
      b.value[w] = *rc::gen::oneOf(rc::gen::inRange(-kMaxWordValue, kMaxWordValue + 1),
                                   rc::gen::inRange(-20'000, 20'001),
                                   rc::gen::element(0, kMaxWordValue, -kMaxWordValue, 10'000, -1));
    }
  }
  return b;
}

RC_GTEST_PROP(GcodeParserProps, TolerantRoundTrip, ()) {
  const Block b = gen_block(false);
  Formatting f{false, *rc::gen::container<std::vector<int>>(kWordCount + 6, rc::gen::inRange(0, 6)),
               *rc::gen::arbitrary<bool>(), *rc::gen::arbitrary<bool>(), *rc::gen::inRange(0, 3)};
  const std::string text = format(b, f);
  const auto r = parse_line(text, 1, L);
  RC_ASSERT(r.error.kind == ErrorKind::None);
  RC_ASSERT(r.block == b);
}

RC_GTEST_PROP(GcodeParserProps, ThesisRoundTripAndTolerantAgrees, ()) {
  const Block b = gen_block(true);
  Formatting f{true, {}, false, *rc::gen::arbitrary<bool>(), *rc::gen::inRange(0, 3)};
  const std::string text = format(b, f);
  const auto t = parse_line(text, 1, T);
  RC_ASSERT(t.error.kind == ErrorKind::None);
  RC_ASSERT(t.block == b);
  const auto l = parse_line(text, 1, L);
  RC_ASSERT(l.error.kind == ErrorKind::None);
  RC_ASSERT(l.block == b);
}

// Any bytes: an error's column lies in 1..length+1, a rejected line gives an empty block,
// and Thesis acceptance implies Tolerant acceptance of the same block (docs/gcode.md).
RC_GTEST_PROP(GcodeParserProps, AnyLineIsSafe, ()) {
  const auto alphabet = rc::gen::oneOf(rc::gen::element<char>('N', 'G', 'M', 'X', 'Y', 'I', 'J', 'F', ' ', '.', '-',
                                                              '+', '(', ')', ';', '%', '\t', '\r', 'g', 'x'),
                                       rc::gen::inRange<char>('0', '9' + 1), rc::gen::arbitrary<char>());
  const std::string text = *rc::gen::container<std::string>(alphabet);
  for (const Dialect d : {T, L}) {
    const auto r = parse_line(text, 9, d);
    RC_ASSERT(r.error.line == 9U);
    if (r.error.ok()) {
      RC_ASSERT(r.error.column == 0);
    } else {
      RC_ASSERT(r.error.column >= 1);
      RC_ASSERT(r.error.column <= std::min<std::size_t>(text.size(), kMaxLineLength) + 1);
      RC_ASSERT(r.block == Block{});
    }
  }
  const auto t = parse_line(text, 9, T);
  if (t.error.ok()) {
    const auto l = parse_line(text, 9, L);
    RC_ASSERT(l.error.ok());
    RC_ASSERT(l.block == t.block);
  }
}

}  // namespace
