// G-code interpreter: the thesis program's 8 moves against the table of seed-003.md §2.5
// (positions typed here in um: X200 = 200 000 um), units and feed conversion from their
// definitions (docs/gcode.md §Units), arcs and grbl's radius tolerance (docs/gcode.md §Arcs),
// each interpreter error with its column, and state properties: a rejected line changes
// nothing; G91 sums equal G90.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/xy/gcode/arc.hpp"
#include "core/xy/gcode/interpreter.hpp"
#include "core/xy/gcode/parser.hpp"
#include "thesis_program.hpp"

namespace {

using namespace ap::xy_gcode;
using P = std::array<std::int32_t, 3>;

// Runs lines (Tolerant) through one interpreter; every line must be accepted.
struct Script {
  Interpreter in;
  std::uint32_t line = 0;

  Move ok(const std::string& s) {
    const auto p = parse_line(s, ++line, Dialect::Tolerant);
    EXPECT_TRUE(p.error.ok()) << s << ": parse " << error_name(p.error.kind);
    const auto r = in.apply(p.block);
    EXPECT_TRUE(r.error.ok()) << s << ": " << error_name(r.error.kind) << " col " << r.error.column;
    return r.move;
  }
  // Expects the interpreter (not the parser) to reject s with kind at column; state unchanged.
  void fails(const std::string& s, ErrorKind kind, std::uint16_t column) {
    const auto p = parse_line(s, ++line, Dialect::Tolerant);
    ASSERT_TRUE(p.error.ok()) << s << ": parse " << error_name(p.error.kind);
    const State before = in.state();
    const auto r = in.apply(p.block);
    EXPECT_EQ(std::string(error_name(r.error.kind)), error_name(kind)) << s;
    EXPECT_EQ(r.error.column, column) << s;
    EXPECT_EQ(r.error.line, line) << s;
    EXPECT_EQ(r.move, Move{}) << s;
    EXPECT_EQ(in.state(), before) << s << ": a rejected line changed the state";
  }
};

Move expected(MoveKind k, P from, P to, std::int32_t feed, std::uint32_t line, std::int32_t n, bool z_only,
              std::int32_t cx = 0, std::int32_t cy = 0) {
  Move m;
  m.kind = k;
  m.from = from;
  m.to = to;
  m.centre_x = cx;
  m.centre_y = cy;
  m.feed_um_s = feed;
  m.line = line;
  m.n = n;
  m.z_only = z_only;
  return m;
}

// ---- the thesis program (seed-003.md §2.5) ----------------------------------------------

TEST(GcodeThesisMoves, EightMovesMatchTheSeedTable) {
  // F2000 mm/min = 2 000 000 um / 60 s = 33 333.3 -> 33 333 um/s (docs/gcode.md §Units).
  constexpr std::int32_t f = 33'333;
  const std::vector<Move> table = {
      expected(MoveKind::Linear, {0, 0, 0}, {200'000, 200'000, 0}, 0, 1, 1, false),  // feed not set yet
      expected(MoveKind::Linear, {200'000, 200'000, 0}, {200'000, 200'000, 0}, f, 2, 2, true),  // Z only
      expected(MoveKind::Linear, {200'000, 200'000, 0}, {200'000, 300'000, 0}, f, 3, 3, false),
      expected(MoveKind::Linear, {200'000, 300'000, 0}, {300'000, 300'000, 0}, f, 4, 4, false),
      expected(MoveKind::ArcCw, {300'000, 300'000, 0}, {300'000, 100'000, 0}, f, 5, 5, false, 300'000, 200'000),
      expected(MoveKind::Linear, {300'000, 100'000, 0}, {100'000, 100'000, 0}, f, 6, 6, false),
      expected(MoveKind::Linear, {100'000, 100'000, 0}, {100'000, 100'000, 10'000}, f, 7, 7, true),  // Z only
      expected(MoveKind::Rapid, {100'000, 100'000, 10'000}, {0, 0, 0}, 0, 8, 8, false),
  };
  const auto lines = gcode_test::thesis_lines();
  ASSERT_EQ(lines.size(), table.size());
  for (const Dialect d : {Dialect::Thesis, Dialect::Tolerant}) {
    Interpreter in;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const auto p = parse_line(lines[i], static_cast<std::uint32_t>(i + 1), d);
      ASSERT_TRUE(p.error.ok()) << lines[i];
      const auto r = in.apply(p.block);
      ASSERT_TRUE(r.error.ok()) << lines[i] << ": " << error_name(r.error.kind);
      EXPECT_EQ(r.move, table[i]) << lines[i];
    }
    EXPECT_EQ(in.state().pos, (P{0, 0, 0}));
    EXPECT_EQ(in.state().motion, Motion::Rapid);
    EXPECT_EQ(in.state().feed_um_s, f);
  }
}

TEST(GcodeThesisMoves, ArcN05IsAHalfCircleOfRadius100mm) {
  Script r;
  r.ok("G1 X300 Y300");
  const Move m = r.ok("G2 Y100 I0 J-100");
  // r = 100 mm from start and from end (seed-003.md §2.5: centre (300,200), passes (400,200)).
  EXPECT_EQ(m.from[1] - m.centre_y, 100'000);
  EXPECT_EQ(m.centre_y - m.to[1], 100'000);
  EXPECT_EQ(m.kind, MoveKind::ArcCw);
}

// ---- modal behaviour ----------------------------------------------------------------------

TEST(GcodeInterp, InitialStateAndModalMotion) {
  Script r;
  EXPECT_EQ(r.in.state(), State{});
  EXPECT_EQ(r.in.state().motion, Motion::None);
  EXPECT_FALSE(r.in.state().incremental);
  EXPECT_FALSE(r.in.state().inches);
  EXPECT_EQ(r.ok("G0 F1500").kind, MoveKind::None);  // seed-003.md §2.2: G0 F1500 sets the feed
  EXPECT_EQ(r.in.state().feed_um_s, 25'000);         // 1500 mm/min = 25 mm/s
  EXPECT_EQ(r.in.state().motion, Motion::Rapid);
  const Move m = r.ok("X12");  // modal G0
  EXPECT_EQ(m.kind, MoveKind::Rapid);
  EXPECT_EQ(m.to, (P{12'000, 0, 0}));
  EXPECT_EQ(m.feed_um_s, 0);  // F does not apply to rapids
  EXPECT_EQ(m.n, -1);
  EXPECT_EQ(r.ok("G1 X90.6 Y13.8").to, (P{90'600, 13'800, 0}));
  EXPECT_EQ(r.ok("Y0").kind, MoveKind::Linear);
  EXPECT_EQ(r.ok("N7 M3").kind, MoveKind::None);  // M codes are kept, never executed (seed-003.md §2.4)
  EXPECT_EQ(r.ok("N8 M3").n, 8);
  EXPECT_EQ(r.ok("").kind, MoveKind::None);
  EXPECT_EQ(r.in.state().pos, (P{90'600, 0, 0}));
}

// Seed 003 Tab. 2 (003_*.txt): "M206 X40 Y40" sets a home offset at 40, 40; it is not a
// move. An M code's words are its parameters (docs/gcode.md "M lines"), whatever the modal
// motion; a G motion word on the same line still takes the axis words.
TEST(GcodeInterp, AnMLineNeverMoves) {
  Script r;
  r.ok("G1 F600");
  const Move m = r.ok("N02 M206 X40 Y40");
  EXPECT_EQ(m.kind, MoveKind::None);
  EXPECT_EQ(r.in.state().pos, (P{0, 0, 0}));
  EXPECT_EQ(r.ok("M106 S127").kind, MoveKind::None);
  EXPECT_EQ(r.ok("M301 P22.2 I1.08 D114").kind, MoveKind::None);
  EXPECT_EQ(r.in.state().pos, (P{0, 0, 0}));
  EXPECT_EQ(r.ok("X5").kind, MoveKind::Linear);  // the modal G1 is still in force
  EXPECT_EQ(r.ok("G1 X7 M3").to, (P{7'000, 0, 0}));
}

TEST(GcodeInterp, IncrementalMode) {
  Script r;
  r.ok("G91 G1 X10 Y-5");
  const Move m = r.ok("X10 Z1");
  EXPECT_EQ(m.from, (P{10'000, -5'000, 0}));
  EXPECT_EQ(m.to, (P{20'000, -5'000, 1'000}));
  r.ok("G90 X1");
  EXPECT_EQ(r.in.state().pos, (P{1'000, -5'000, 1'000}));
}

TEST(GcodeInterp, ZOnlyMeansNoXyMotion) {
  Script r;
  EXPECT_TRUE(r.ok("G1 Z5").z_only);
  EXPECT_FALSE(r.ok("G1 X1 Z5").z_only);
  EXPECT_TRUE(r.ok("G1 X1").z_only);  // already at X1: no XY motion
  EXPECT_TRUE(r.ok("G0 Z0").z_only);
}

// ---- units (docs/gcode.md §Units): 1 in = 25 400 um exactly, half away from zero ----------

TEST(GcodeUnits, InchPositions) {
  Script r;
  EXPECT_EQ(r.ok("G20 G1 X1").to[0], 25'400);
  EXPECT_EQ(r.ok("X0.0001").to[0], 3);     // 2.54 um -> 3
  EXPECT_EQ(r.ok("X-0.0001").to[0], -3);   // -2.54 um -> -3
  EXPECT_EQ(r.ok("X0.0002").to[0], 5);     // 5.08 um -> 5
  EXPECT_EQ(r.ok("X0.0003").to[0], 8);     // 7.62 um -> 8
  EXPECT_EQ(r.ok("X0.0025").to[0], 64);    // 63.5 um -> 64 (tie, away from zero)
  EXPECT_EQ(r.ok("X-0.0025").to[0], -64);  // -63.5 um -> -64
  EXPECT_EQ(r.ok("X393.7008").to[0], 10'000'000);  // 10 000 000.32 um: inside +-10 m
  EXPECT_EQ(r.ok("X-2.5 Y1.5").to, (P{-63'500, 38'100, 0}));
  EXPECT_EQ(r.ok("G21 X1").to[0], 1'000);
}

TEST(GcodeUnits, MillimetrePositions) {
  Script r;
  EXPECT_EQ(r.ok("G1 X0.0004").to[0], 0);   // 0.4 um -> 0
  EXPECT_EQ(r.ok("X0.0005").to[0], 1);      // 0.5 um -> 1 (tie, away from zero)
  EXPECT_EQ(r.ok("X-0.0005").to[0], -1);
  EXPECT_EQ(r.ok("X-0.0015").to[0], -2);    // -1.5 -> -2
  EXPECT_EQ(r.ok("X10000").to[0], 10'000'000);
  EXPECT_EQ(r.ok("X-10000").to[0], -10'000'000);
}

TEST(GcodeUnits, Feed) {
  Script r;
  r.ok("G1 F60");
  EXPECT_EQ(r.in.state().feed_um_s, 1'000);    // 60 mm/min = 1 mm/s
  r.ok("F2000");
  EXPECT_EQ(r.in.state().feed_um_s, 33'333);   // 33 333.3
  r.ok("F4000");
  EXPECT_EQ(r.in.state().feed_um_s, 66'667);   // 66 666.7
  r.ok("F0.03");
  EXPECT_EQ(r.in.state().feed_um_s, 1);        // 0.5 um/s -> 1
  r.ok("G20 F1");
  EXPECT_EQ(r.in.state().feed_um_s, 423);      // 25 400 / 60 = 423.3
  r.ok("F60");
  EXPECT_EQ(r.in.state().feed_um_s, 25'400);
  r.ok("F99999.9999");
  EXPECT_EQ(r.in.state().feed_um_s, 42'333'333);
  EXPECT_EQ(kMaxFeedUmS, 42'333'333);
  // G20/G21 on a line apply to the F on that line (grbl's order).
  Script s;
  const Move m = s.ok("G20 G1 X1 F60");
  EXPECT_EQ(m.to[0], 25'400);
  EXPECT_EQ(m.feed_um_s, 25'400);
  // A later unit change does not rescale the stored feed: it is a speed.
  s.ok("G21");
  EXPECT_EQ(s.in.state().feed_um_s, 25'400);
}

TEST(GcodeUnits, RoundingHelper) {
  EXPECT_EQ(div_round_half_away(5, 10), 1);
  EXPECT_EQ(div_round_half_away(-5, 10), -1);
  EXPECT_EQ(div_round_half_away(4, 10), 0);
  EXPECT_EQ(div_round_half_away(-4, 10), 0);
  EXPECT_EQ(div_round_half_away(15, 10), 2);
  EXPECT_EQ(div_round_half_away(-25, 10), -3);
  EXPECT_EQ(length_um(kMaxWordValue, true), 2'539'999'997);  // 99999.9999 in = 2 539 999 997.46 um
  EXPECT_EQ(length_um(-kMaxWordValue, false), -100'000'000);  // -99999.9999 mm = -99 999 999.9 um
}

// ---- arcs (docs/gcode.md §Arcs) ----------------------------------------------------------

TEST(GcodeArc, CentreIsIncrementalInBothDistanceModes) {
  Script a;
  a.ok("G1 X10 Y10");
  const Move m = a.ok("G3 X30 Y10 I10 J0");
  EXPECT_EQ(m.centre_x, 20'000);
  EXPECT_EQ(m.centre_y, 10'000);
  EXPECT_EQ(m.kind, MoveKind::ArcCcw);
  Script b;
  b.ok("G1 X10 Y10");
  const Move n = b.ok("G91 G3 X20 Y0 I10 J0");
  EXPECT_EQ(n.to, (P{30'000, 10'000, 0}));
  EXPECT_EQ(n.centre_x, 20'000);  // not 10 000 (I as absolute) nor start + end
  EXPECT_EQ(n.centre_y, 10'000);
}

TEST(GcodeArc, FullCircleAndHelix) {
  Script r;
  const Move m = r.ok("G2 X0 Y0 I10");
  EXPECT_EQ(m.kind, MoveKind::ArcCw);
  EXPECT_EQ(m.from, m.to);
  EXPECT_EQ(m.centre_x, 10'000);
  EXPECT_EQ(m.centre_y, 0);
  const Move h = r.ok("G2 Z-1 J5");  // end XY == start: a full helical turn
  EXPECT_EQ(h.to, (P{0, 0, -1'000}));
  EXPECT_EQ(h.centre_y, 5'000);
  EXPECT_FALSE(h.z_only);
}

TEST(GcodeArc, RadiusToleranceBoundaries) {
  // grbl's tolerance max(5 um, min(500 um, 0.1 % r)); start (0,0), centre (r,0), end (2r+d,0):
  // end radius r+d.
  struct C {
    const char* line;
    bool accepted;
  };
  for (const C& c : std::vector<C>{
           {"G2 X2.005 I1", true},     // r = 1 mm: tolerance 5 um, d = 5
           {"G2 X2.006 I1", false},    // d = 6
           {"G2 X1.995 I1", true},     // d = -5
           {"G2 X1.994 I1", false},    // d = -6
           {"G2 X20.01 I10", true},    // r = 10 mm: 0.1 % = 10 um, d = 10
           {"G2 X20.011 I10", false},  // d = 11
           {"G2 X19.989 I10", false},  // d = -11
           {"G2 X200.1 I100", true},   // r = 100 mm (thesis N05): 100 um
           {"G2 X200.101 I100", false},
           {"G2 X2000.5 I1000", true},   // r = 1 m: 0.1 % = 1 mm, capped at 0.5 mm
           {"G2 X2000.501 I1000", false},
           {"G2 X1999.499 I1000", false},
           {"G2 X0.01 I0.005", true},    // r = 5 um, end radius 5 um
           {"G2 X0.02 I0.005", false},   // end radius 15 um: d = 10 > 5
       }) {
    Script r;
    const auto p = parse_line(c.line, 1, Dialect::Tolerant);
    ASSERT_TRUE(p.error.ok()) << c.line;
    const auto res = r.in.apply(p.block);
    if (c.accepted) {
      EXPECT_TRUE(res.error.ok()) << c.line << ": " << error_name(res.error.kind);
    } else {
      EXPECT_EQ(res.error.kind, ErrorKind::ArcRadiusMismatch) << c.line;
      EXPECT_EQ(res.error.column, 4) << c.line;
    }
  }
  // The end off the circle in Y: r = 100 mm, end (100, 100.2) has radius 100.2 mm.
  Script r;
  r.fails("G3 X100 Y100.2 I100", ErrorKind::ArcRadiusMismatch, 4);
  r.ok("G3 X100 Y100.1 I100");  // sqrt(100^2 + 100.1^2) vs ... end radius 100.1 mm: d = 100 um
}

// sqrt_gap_exceeds against a long double reference away from the boundary, and exactly at
// perfect squares.
RC_GTEST_PROP(GcodeArcProps, SqrtGapMatchesReference, ()) {
  const auto a = *rc::gen::inRange<std::uint64_t>(0, std::uint64_t{1} << 51);
  const auto b = *rc::gen::oneOf(rc::gen::inRange<std::uint64_t>(0, std::uint64_t{1} << 51),
                                 rc::gen::inRange<std::uint64_t>(a, a + 100'000'000));
  const auto t = *rc::gen::element<std::uint64_t>(0, 5, 500, 1000);
  const long double gap = std::sqrt(static_cast<long double>(b)) - std::sqrt(static_cast<long double>(a));
  RC_PRE(std::fabs(gap - static_cast<long double>(t)) > 1e-6L);
  RC_ASSERT(sqrt_gap_exceeds(a, b, t) == (gap > static_cast<long double>(t)));
}

RC_GTEST_PROP(GcodeArcProps, SqrtGapExactAtSquares, ()) {
  const auto x = *rc::gen::inRange<std::uint64_t>(0, 40'000'000);
  const auto t = *rc::gen::element<std::uint64_t>(5, 500, 1000);
  const auto y = x + t;
  RC_ASSERT(!sqrt_gap_exceeds(x * x, y * y, t));         // gap == t: not more
  RC_ASSERT(sqrt_gap_exceeds(x * x, y * y + 1, t));      // just more
  RC_ASSERT(!sqrt_gap_exceeds(y * y, x * x, t));         // negative gap
}

// ---- interpreter errors, exact columns, state unchanged ------------------------------------

TEST(GcodeInterpErrors, NoMotionMode) {
  Script r;
  r.fails("X10", ErrorKind::NoMotionMode, 1);
  r.fails("G90 Y5 X10", ErrorKind::NoMotionMode, 5);
  r.fails("F100 Z1", ErrorKind::NoMotionMode, 6);
  r.fails("N3 G91 (c) X1", ErrorKind::NoMotionMode, 12);
}

TEST(GcodeInterpErrors, PositionOutOfRange) {
  Script r;
  r.fails("G1 X10000.001", ErrorKind::PositionOutOfRange, 4);
  r.fails("G1 X1 Y-10000.0005", ErrorKind::PositionOutOfRange, 7);  // -10 000 000.5 -> -10 000 001
  r.fails("G20 G1 X393.7009", ErrorKind::PositionOutOfRange, 8);     // 10 000 002.9 um
  r.fails("G0 Z99999", ErrorKind::PositionOutOfRange, 4);
  r.ok("G91 G1 X6000");
  r.fails("X6000", ErrorKind::PositionOutOfRange, 1);  // 12 m after two increments
  r.ok("G90 X0");
  r.fails("G2 X0 I-10000.001", ErrorKind::PositionOutOfRange, 7);  // centre beyond 10 m
  r.fails("G2 X0 I1 J10000.001", ErrorKind::PositionOutOfRange, 10);
}

TEST(GcodeInterpErrors, ArcWithoutCentre) {
  Script r;
  r.fails("G2 X10 Y0", ErrorKind::ArcWithoutCentre, 1);
  r.fails("N1 G3 X10", ErrorKind::ArcWithoutCentre, 4);
  r.ok("G2 X10 I5");
  r.fails("X0", ErrorKind::ArcWithoutCentre, 1);  // modal arc: the first axis word
  r.fails("Y2 X0", ErrorKind::ArcWithoutCentre, 1);
}

TEST(GcodeInterpErrors, ArcZeroRadius) {
  Script r;
  r.fails("G2 X0 I0 J0", ErrorKind::ArcZeroRadius, 7);
  r.fails("G3 X0 J0", ErrorKind::ArcZeroRadius, 7);
  r.fails("G2 X1 I0.0004", ErrorKind::ArcZeroRadius, 7);  // 0.4 um rounds to 0
}

TEST(GcodeInterpErrors, UnusedWord) {
  Script r;
  r.fails("G1 X1 I1", ErrorKind::UnusedWord, 7);
  r.fails("G0 J5 X1", ErrorKind::UnusedWord, 4);
  r.fails("I5", ErrorKind::UnusedWord, 1);
  r.fails("G2 I5 J5", ErrorKind::UnusedWord, 4);  // no axis word: no motion, the centre is unused
}

TEST(GcodeInterpErrors, BadFeed) {
  Script r;
  r.fails("G1 F0", ErrorKind::BadFeed, 4);
  r.fails("G1 X1 F-100", ErrorKind::BadFeed, 7);
  r.fails("F0.0001", ErrorKind::BadFeed, 1);  // 1/600 um/s rounds to 0
  r.fails("F0.0299", ErrorKind::BadFeed, 1);  // 0.498 um/s rounds to 0
  r.ok("F0.03");                             // 0.5 um/s -> 1 (tie, away from zero)
  EXPECT_EQ(r.in.state().feed_um_s, 1);
}

TEST(GcodeInterpErrors, RejectedLineKeepsModalWords) {
  // Every modal word on a rejected line is dropped with it (grbl/LinuxCNC: an erroneous
  // block is not executed at all).
  Script r;
  r.ok("G1 X1 F60");
  r.fails("G20 G91 G0 X1 I1 F10", ErrorKind::UnusedWord, 15);
  EXPECT_EQ(r.in.state().motion, Motion::Linear);
  EXPECT_FALSE(r.in.state().inches);
  EXPECT_FALSE(r.in.state().incremental);
  EXPECT_EQ(r.in.state().feed_um_s, 1'000);
}

// ---- properties ----------------------------------------------------------------------------

// A random Block, mostly in range, with rare out-of-range values and odd combinations.
Block gen_any_block() {
  Block b;
  b.motion = static_cast<Motion>(*rc::gen::inRange(0, 5));
  b.units = static_cast<Units>(*rc::gen::inRange(0, 3));
  b.distance = static_cast<Distance>(*rc::gen::inRange(0, 3));
  b.present = *rc::gen::inRange<std::uint8_t>(0, 64);
  for (std::size_t w = 0; w < kWordCount; ++w) {
    if (b.present & (1U << w)) {
      b.value[w] = *rc::gen::oneOf(rc::gen::inRange(-2'000'000, 2'000'001),
                                   rc::gen::inRange(-kMaxWordValue, kMaxWordValue + 1), rc::gen::element(0, 1, -1));
      b.column[w] = static_cast<std::uint16_t>(10 + w);
    }
  }
  b.motion_column = b.motion != Motion::None ? 1 : 0;
  b.line = *rc::gen::inRange<std::uint32_t>(1, 1000);
  return b;
}

RC_GTEST_PROP(GcodeInterpProps, RejectedLineChangesNoState, ()) {
  Interpreter in;
  const int history = *rc::gen::inRange(0, 30);
  for (int i = 0; i < history; ++i) (void)in.apply(gen_any_block());
  const State before = in.state();
  const Block b = gen_any_block();
  const auto r = in.apply(b);
  if (!r.error.ok()) {
    RC_ASSERT(in.state() == before);
    RC_ASSERT(r.move == Move{});
    RC_ASSERT(r.error.line == b.line);
    RC_ASSERT(r.error.column >= 1);
  } else {
    RC_ASSERT(r.move.from == before.pos);
    RC_ASSERT(r.move.to == in.state().pos);
  }
  for (const auto c : in.state().pos) RC_ASSERT(c >= -kMaxPositionUm && c <= kMaxPositionUm);
  RC_ASSERT(in.state().feed_um_s >= 0 && in.state().feed_um_s <= kMaxFeedUmS);
  for (const auto c : {r.move.centre_x, r.move.centre_y}) RC_ASSERT(c >= -kMaxPositionUm && c <= kMaxPositionUm);
}

// Whole-micrometre increments (mm words in multiples of 0.001; inch words in multiples of
// 0.005 in = 127 um): G91 steps land exactly where G90 with the running sums lands.
RC_GTEST_PROP(GcodeInterpProps, IncrementalSumsEqualAbsolute, ()) {
  const bool inches = *rc::gen::arbitrary<bool>();
  const std::int32_t unit = inches ? 50 : 10;  // 1e-4 units per whole-um step
  const std::int32_t um_per_unit_step = inches ? 127 : 1;
  // Bounds: <= 100 steps (RapidCheck's default size) of <= 50 mm (mm) or 500 * 127 um =
  // 63.5 mm (inch) per axis stay inside +-10 m.
  const std::int32_t bound = inches ? 500 : 50'000;
  const auto steps = *rc::gen::container<std::vector<std::array<std::int32_t, 3>>>(
      rc::gen::container<std::array<std::int32_t, 3>>(rc::gen::inRange(-bound, bound + 1)));
  RC_PRE(steps.size() <= 100U);
  Interpreter inc;
  Interpreter abs;
  Block setup;
  setup.units = inches ? Units::Inch : Units::Millimetre;
  setup.motion = Motion::Linear;
  setup.distance = Distance::Incremental;
  RC_ASSERT(inc.apply(setup).error.ok());
  setup.distance = Distance::Absolute;
  RC_ASSERT(abs.apply(setup).error.ok());
  std::array<std::int64_t, 3> sum{};
  for (const auto& s : steps) {
    Block i;
    Block a;
    i.present = a.present = Block::bit(Word::X) | Block::bit(Word::Y) | Block::bit(Word::Z);
    for (std::size_t k = 0; k < 3; ++k) {
      sum[k] += s[k];
      i.value[k] = s[k] * unit;
      a.value[k] = static_cast<std::int32_t>(sum[k] * unit);
    }
    const auto ri = inc.apply(i);
    const auto ra = abs.apply(a);
    RC_ASSERT(ri.error.ok());
    RC_ASSERT(ra.error.ok());
    RC_ASSERT(ri.move == ra.move);
    for (std::size_t k = 0; k < 3; ++k) RC_ASSERT(ri.move.to[k] == sum[k] * um_per_unit_step);
  }
}

}  // namespace
