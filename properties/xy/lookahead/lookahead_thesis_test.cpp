// The thesis's look-ahead code (seed-003.md §6, transcribed literally in models/xy/lookahead) and its
// defects a-e as regressions: each test shows the thesis model's answer and the core's.
// Then the thesis's test program (seed-003.md §2.5, 20 steps/mm) junction by junction.
// Expected values are typed from the thesis law and hand calculation (docs/lookahead.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/xy/lookahead/junction.hpp"
#include "models/xy/lookahead/lookahead.hpp"

using namespace ap::xy_lookahead;
namespace ref = ap::model::xy_lookahead;

namespace {
Direction xy(int64_t x, int64_t y) { return line_direction(x, y, 0); }
ref::ThesisSegment rows(std::initializer_list<std::pair<double, double>> r) { return ref::ThesisSegment{r}; }
}  // namespace

// (a) -atan(uy/ux) for ux < 0 is not atan2: (-1, 1) gets +45, like (1, 1), so a 90 deg corner
// looks straight (factor 1). The core sees 90 deg: full stop.
TEST(LookaheadThesisDefects, A_MinusAtanIsNotAtan2) {
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(-1, 1), 45.0);
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(1, 1), 45.0);
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(-1, -1), -45.0);
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(1, -1), -45.0);
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(rows({{1, 1}}), rows({{-1, 1}})), 1.0);  // thesis: straight
  const Junction j = junction(xy(1, 1), xy(-1, 1));
  EXPECT_EQ(j.turn_mdeg, 90'000);
  EXPECT_EQ(j.factor_permille, 0);
  EXPECT_EQ(j.kind, JunctionKind::Stop);
  // (1, -1) then (-1, -1): the same 90 deg corner mirrored.
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(rows({{1, -1}}), rows({{-1, -1}})), 1.0);
  EXPECT_EQ(junction(xy(1, -1), xy(-1, -1)).factor_permille, 0);
}

// (b) No wrap-around: headings 170 and -170 deg differ by 340 in the thesis code, so it stops;
// the turn is 20 deg, factor 1 - 20/90 = 0.7778 -> 778.
TEST(LookaheadThesisDefects, B_NoWrapAround) {
  EXPECT_DOUBLE_EQ(ref::thesis_factor(170, -170), 0.0);
  // cos/sin 170 deg * 1e6, rounded: the turn is 19.999975 deg.
  const Junction j = junction(xy(-984'808, 173'648), xy(-984'808, -173'648));
  EXPECT_EQ(j.turn_mdeg, 20'000);
  EXPECT_EQ(j.factor_permille, 778);
  EXPECT_EQ(j.kind, JunctionKind::Corner);
  // With the thesis's own angle code: -X (180) then (-10, -1) (thesis -5.71, atan2 -174.29):
  // thesis |(-5.71) - 180| = 185.7 -> stop; the turn is atan(0.1) = 5.7106 deg -> 937.
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(rows({{-1, 0}}), rows({{-10, -1}})), 0.0);
  const Junction k = junction(xy(-1, 0), xy(-10, -1));
  EXPECT_EQ(k.turn_mdeg, 5'711);
  EXPECT_EQ(k.factor_permille, 937);
}

// (c) A Z-only (or zero-length) segment has ux = uy = 0: atan(0/0) = NaN, and the NaN factor
// follows. The core: ZOnly -> full stop both sides; nothing moving -> drop the segment.
TEST(LookaheadThesisDefects, C_ZOnlyIsNaN) {
  EXPECT_TRUE(std::isnan(ref::thesis_angle_deg(0, 0)));
  EXPECT_TRUE(std::isnan(ref::thesis_junction_factor(rows({{4000, 4000}}), rows({{0, 0}}))));
  EXPECT_TRUE(std::isnan(ref::thesis_junction_factor(rows({{0, 0}}), rows({{0, 2000}}))));
  const Direction z = line_direction(0, 0, 200);
  EXPECT_EQ(z.kind, DirectionKind::ZOnly);
  const Junction in = junction(xy(4000, 4000), z);
  const Junction out = junction(z, xy(0, 2000));
  EXPECT_EQ(in.kind, JunctionKind::ZOnlyStop);
  EXPECT_EQ(in.factor_permille, 0);
  EXPECT_EQ(out.kind, JunctionKind::ZOnlyStop);
  EXPECT_EQ(out.factor_permille, 0);
  EXPECT_TRUE(drop_segment(line_direction(0, 0, 0)));
}

// (d) ux = 0: atan(+-Inf) = +-90, which is right; the thesis model and the core agree.
TEST(LookaheadThesisDefects, D_VerticalIsFine) {
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(0, 2000), 90.0);
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(0, -5), -90.0);
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(rows({{1, 0}}), rows({{0, 1}})), 0.0);
  EXPECT_EQ(junction(xy(1, 0), xy(0, 1)).factor_permille, 0);
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(rows({{0, 1}}), rows({{0, 7}})), 1.0);
  EXPECT_EQ(junction(xy(0, 1), xy(0, 7)).factor_permille, 1000);
}

// (e) Only row 1 of each segment is compared: after an arc the thesis compares the next
// segment with the arc's *start* tangent. N05 (CW half circle, starts moving +X, ends moving
// -X) then N06 (-X): thesis 180 deg -> stop; the core uses the end tangent: tangent, 1000.
TEST(LookaheadThesisDefects, E_OnlyRowOneCompared) {
  const ref::ThesisSegment n05 = rows({{2000, 0}, {0, -2000}, {-2000, 0}});  // tangents, start to end
  const ref::ThesisSegment n06 = rows({{-4000, 0}});
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(n05, n06), 0.0);
  const Junction j = junction(arc_end_direction(0, -2000, Turn::Cw), xy(-4000, 0));
  EXPECT_EQ(j.kind, JunctionKind::Straight);
  EXPECT_EQ(j.factor_permille, 1000);
}

// seed-003.md §2.5 in steps (20 steps/mm): N01 (0,0)->(4000,4000); N02 Z only; N03 ->(4000,6000);
// N04 ->(6000,6000); N05 G02 centre (6000,4000) -> (6000,2000); N06 ->(2000,2000); N07 Z only;
// N08 ->(0,0) (with Z: its XY projection).
TEST(LookaheadThesisProgram, Junctions) {
  const Direction n01 = line_direction(4000, 4000, 0);
  const Direction n02 = line_direction(0, 0, -1);  // Z0 from wherever Z was (see docs)
  const Direction n03 = line_direction(0, 2000, 0);
  const Direction n04 = line_direction(2000, 0, 0);
  const Direction n05s = arc_start_direction(6000 - 6000, 6000 - 4000, Turn::Cw);
  const Direction n05e = arc_end_direction(6000 - 6000, 2000 - 4000, Turn::Cw);
  const Direction n06 = line_direction(-4000, 0, 0);
  const Direction n07 = line_direction(0, 0, 200);  // Z10 = 200 steps
  const Direction n08 = line_direction(-2000, -2000, -200);
  struct Case {
    const char* name;
    Direction in, out;
    int32_t turn;
    uint16_t factor;
    JunctionKind kind;
    uint32_t speed;  // v_max 1000 steps/s (50 mm/s), v_jump 100 steps/s
  };
  for (const Case& c : {
           Case{"N01-N02", n01, n02, 0, 0, JunctionKind::ZOnlyStop, 0},
           Case{"N02-N03", n02, n03, 0, 0, JunctionKind::ZOnlyStop, 0},
           Case{"N03-N04", n03, n04, 90'000, 0, JunctionKind::Stop, 0},
           Case{"N04-N05", n04, n05s, 0, 1000, JunctionKind::Straight, 1000},
           Case{"N05-N06", n05e, n06, 0, 1000, JunctionKind::Straight, 1000},
           Case{"N06-N07", n06, n07, 0, 0, JunctionKind::ZOnlyStop, 0},
           Case{"N07-N08", n07, n08, 0, 0, JunctionKind::ZOnlyStop, 0},
           // Had N02 / N07 moved nothing (Z already there), they are dropped and the
           // neighbours meet: 45 deg, factor 500, per-axis cap 100 / sin 45 = 141.
           Case{"N01-N03", n01, n03, 45'000, 500, JunctionKind::Corner, 141},
           Case{"N06-N08", n06, n08, 45'000, 500, JunctionKind::Corner, 141},
       }) {
    SCOPED_TRACE(c.name);
    const Junction j = junction(c.in, c.out);
    EXPECT_EQ(j.turn_mdeg, c.turn);
    EXPECT_EQ(j.factor_permille, c.factor);
    EXPECT_EQ(j.kind, c.kind);
    EXPECT_EQ(junction_speed(1000, j, c.in, c.out, 100), c.speed);
  }
  EXPECT_EQ(n05s.x, 2000);  // N05 starts moving +X (CW on top of the circle)
  EXPECT_EQ(n05s.y, 0);
  EXPECT_EQ(n05e.x, -2000);  // and ends moving -X
  EXPECT_EQ(n05e.y, 0);
}

// The thesis model on the same program: NaN around the Z-only moves, a stop after the arc
// (defect e), and a stop at N06-N08 (defects a + b: -45 vs 180).
TEST(LookaheadThesisProgram, ThesisModelAnswers) {
  const auto n01 = rows({{4000, 4000}});
  const auto z = rows({{0, 0}});
  const auto n03 = rows({{0, 2000}});
  const auto n04 = rows({{2000, 0}});
  const auto n05 = rows({{2000, 0}, {0, -2000}, {-2000, 0}});
  const auto n06 = rows({{-4000, 0}});
  const auto n08 = rows({{-2000, -2000}});
  EXPECT_TRUE(std::isnan(ref::thesis_junction_factor(n01, z)));
  EXPECT_TRUE(std::isnan(ref::thesis_junction_factor(z, n03)));
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(n03, n04), 0.0);
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(n04, n05), 1.0);
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(n05, n06), 0.0);  // core: 1000
  EXPECT_TRUE(std::isnan(ref::thesis_junction_factor(n06, z)));
  EXPECT_TRUE(std::isnan(ref::thesis_junction_factor(z, n08)));
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(n01, n03), 0.5);  // agrees with the core
  EXPECT_DOUBLE_EQ(ref::thesis_angle_deg(-2000, -2000), -45.0);
  EXPECT_DOUBLE_EQ(ref::thesis_junction_factor(n06, n08), 0.0);  // core: 500
}
