// Junctions (core/xy/lookahead/junction.hpp): directions, the thesis law (seed-003.md §6),
// invariance properties, and the per-axis junction speed cap against the double reference
// (models/xy/lookahead). Expected numbers are typed from the thesis law and hand calculation
// (docs/lookahead.md); rounding is half up, capped at 999 for any non-straight junction.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/xy/lookahead/junction.hpp"
#include "models/xy/lookahead/lookahead.hpp"

using namespace ap::xy_lookahead;
namespace ref = ap::model::xy_lookahead;

namespace {

Direction xy(int64_t x, int64_t y) { return line_direction(x, y, 0); }

// A random non-zero in-range XY direction; half of them small (|c| <= 50, many exact
// parallels, right angles and reversals), half over the whole component range.
rc::Gen<Direction> gen_direction() {
  return rc::gen::suchThat(
      rc::gen::map(rc::gen::tuple(rc::gen::arbitrary<bool>(), rc::gen::inRange<int64_t>(-50, 51),
                                  rc::gen::inRange<int64_t>(-50, 51),
                                  rc::gen::inRange<int64_t>(-kComponentMax, kComponentMax + 1),
                                  rc::gen::inRange<int64_t>(-kComponentMax, kComponentMax + 1)),
                   [](const std::tuple<bool, int64_t, int64_t, int64_t, int64_t>& t) {
                     const auto& [small, sx, sy, lx, ly] = t;
                     return small ? xy(sx, sy) : xy(lx, ly);
                   }),
      [](const Direction& d) { return d.has_direction(); });
}

double dbl(int64_t v) { return static_cast<double>(v); }

bool same(const Junction& a, const Junction& b) {
  return a.turn_mdeg == b.turn_mdeg && a.factor_permille == b.factor_permille && a.kind == b.kind;
}

}  // namespace

// ---- the law --------------------------------------------------------------------------------

TEST(LookaheadFactor, ThesisLawCases) {
  struct Case {
    int32_t turn;
    uint16_t factor;
  };
  // seed-003.md §6: 1 - t/90 below 90 deg, 0 above; rounded half up, 999 cap (docs).
  for (const Case c : {Case{0, 1000}, Case{30'000, 667}, Case{45'000, 500}, Case{20'000, 778}, Case{60'000, 333},
                       Case{89'999, 0}, Case{89'955, 1}, Case{89'954, 1}, Case{90'000, 0}, Case{120'000, 0},
                       Case{180'000, 0}, Case{1, 999}, Case{45, 999}, Case{46, 999}, Case{135, 999}, Case{136, 998},
                       Case{-1, 0}, Case{180'001, 0}, Case{std::numeric_limits<int32_t>::min(), 0}}) {
    EXPECT_EQ(speed_factor_permille(c.turn), c.factor) << "turn " << c.turn;
  }
}

// Exhaustive over every turn in mdeg: non-increasing, in [0, 1000], within 0.5 of the real
// law except the 999 cap (turns < 45 mdeg, where the law is in (999.5, 1000)).
TEST(LookaheadFactor, MonotoneAndWithinRoundingEverywhere) {
  uint16_t prev = 1000;
  for (int32_t t = 0; t <= 180'000; ++t) {
    const uint16_t f = speed_factor_permille(t);
    ASSERT_LE(f, prev) << "turn " << t;
    const double law = 1000.0 * ref::ref_factor(t / 1000.0);
    ASSERT_LE(std::abs(f - law), (t > 0 && t < 45 ? 1.0 : 0.5) + 1e-9) << "turn " << t;
    prev = f;
  }
}

// ---- directions -----------------------------------------------------------------------------

TEST(LookaheadDirection, LineKinds) {
  const Direction d = line_direction(3, -4, 7);
  EXPECT_EQ(d.kind, DirectionKind::Xy);
  EXPECT_EQ(d.x, 3);
  EXPECT_EQ(d.y, -4);
  EXPECT_TRUE(d.has_direction());
  EXPECT_EQ(line_direction(0, 0, 200).kind, DirectionKind::ZOnly);
  EXPECT_EQ(line_direction(0, 0, -1).kind, DirectionKind::ZOnly);
  EXPECT_EQ(line_direction(0, 0, 0).kind, DirectionKind::None);
  EXPECT_TRUE(drop_segment(line_direction(0, 0, 0)));
  EXPECT_FALSE(drop_segment(line_direction(0, 0, 1)));
  EXPECT_FALSE(drop_segment(line_direction(1, 0, 0)));
  EXPECT_EQ(line_direction(kComponentMax, -kComponentMax, 0).kind, DirectionKind::Xy);
  for (const Direction bad : {line_direction(kComponentMax + 1, 0, 0), line_direction(0, -kComponentMax - 1, 0),
                              line_direction(std::numeric_limits<int64_t>::min(), 0, 0)}) {
    EXPECT_EQ(bad.kind, DirectionKind::OutOfRange);
    EXPECT_EQ(bad.x, 0);
    EXPECT_EQ(bad.y, 0);
  }
}

// CW tangent (y, -x), CCW (-y, x) at a point relative to the centre: on top of the circle a CW
// arc moves +X, a CCW arc -X; at the right-hand point CW moves -Y, CCW +Y.
TEST(LookaheadDirection, ArcTangents) {
  struct Case {
    int64_t px, py;
    Turn turn;
    int64_t tx, ty;
  };
  for (const Case c : {Case{0, 2000, Turn::Cw, 2000, 0}, Case{0, 2000, Turn::Ccw, -2000, 0},
                       Case{2000, 0, Turn::Cw, 0, -2000}, Case{2000, 0, Turn::Ccw, 0, 2000},
                       Case{0, -2000, Turn::Cw, -2000, 0}, Case{-3, 4, Turn::Cw, 4, 3}}) {
    const Direction s = arc_start_direction(c.px, c.py, c.turn);
    const Direction e = arc_end_direction(c.px, c.py, c.turn);
    for (const Direction& d : {s, e}) {
      EXPECT_EQ(d.kind, DirectionKind::Xy);
      EXPECT_EQ(d.x, c.tx) << c.px << "," << c.py;
      EXPECT_EQ(d.y, c.ty) << c.px << "," << c.py;
    }
  }
  EXPECT_EQ(arc_start_direction(0, 0, Turn::Cw).kind, DirectionKind::None);
  EXPECT_EQ(arc_end_direction(kComponentMax + 1, 0, Turn::Ccw).kind, DirectionKind::OutOfRange);
}

// ---- junctions ------------------------------------------------------------------------------

TEST(LookaheadJunction, TypedCases) {
  struct Case {
    int64_t x1, y1, x2, y2;
    int32_t turn;
    uint16_t factor;
    JunctionKind kind;
  };
  for (const Case c : {
           Case{3, 4, 6, 8, 0, 1000, JunctionKind::Straight},                  // collinear, other length
           Case{1, 0, 1, 1, 45'000, 500, JunctionKind::Corner},                // 45 deg
           Case{1, 0, 0, 1, 90'000, 0, JunctionKind::Stop},                    // 90 deg: exactly dot = 0
           Case{1, 0, 0, -1, 90'000, 0, JunctionKind::Stop},                   // right turn, same
           Case{1, 0, -1'000'000, 1'732'051, 120'000, 0, JunctionKind::Stop},  // 119.999997 deg
           Case{1, 0, 1'732'051, 1'000'000, 30'000, 667, JunctionKind::Corner},  // 29.999997 deg
           Case{1, 0, 1'732'051, -1'000'000, 30'000, 667, JunctionKind::Corner},
           Case{1, 0, -1, 0, 180'000, 0, JunctionKind::Stop},                  // reversal
           Case{5, 0, 984'808, 173'648, 10'000, 889, JunctionKind::Corner},    // 10.0000 deg
       }) {
    SCOPED_TRACE(testing::Message() << c.x1 << "," << c.y1 << " -> " << c.x2 << "," << c.y2);
    const Junction j = junction(xy(c.x1, c.y1), xy(c.x2, c.y2));
    EXPECT_EQ(j.turn_mdeg, c.turn);
    EXPECT_EQ(j.factor_permille, c.factor);
    EXPECT_EQ(j.kind, c.kind);
  }
}

// A turn far below 1 mdeg is still a turn: never full speed (1000 only for exact parallels).
TEST(LookaheadJunction, TinyTurnIsNotStraight) {
  const Junction j = junction(xy(kComponentMax, 0), xy(kComponentMax, 1));  // 2.7e-5 mdeg
  EXPECT_EQ(j.kind, JunctionKind::Corner);
  EXPECT_EQ(j.turn_mdeg, 1);
  EXPECT_EQ(j.factor_permille, 999);
  const Junction k = junction(xy(kComponentMax, kComponentMax - 1), xy(kComponentMax - 1, kComponentMax - 2));
  EXPECT_EQ(k.kind, JunctionKind::Corner);
  EXPECT_EQ(k.factor_permille, 999);
}

TEST(LookaheadJunction, NonXySidesStop) {
  const Direction z = line_direction(0, 0, 200);
  const Direction none = line_direction(0, 0, 0);
  const Direction bad = line_direction(kComponentMax + 1, 0, 0);
  const Direction a = xy(1, 0);
  struct Case {
    Direction in, out;
    JunctionKind kind;
  };
  for (const Case c : {Case{a, z, JunctionKind::ZOnlyStop}, Case{z, a, JunctionKind::ZOnlyStop},
                       Case{z, z, JunctionKind::ZOnlyStop}, Case{a, none, JunctionKind::NoDirection},
                       Case{none, z, JunctionKind::NoDirection}, Case{bad, a, JunctionKind::Invalid},
                       Case{z, bad, JunctionKind::Invalid}}) {
    const Junction j = junction(c.in, c.out);
    EXPECT_EQ(j.kind, c.kind);
    EXPECT_EQ(j.factor_permille, 0);
    EXPECT_EQ(j.turn_mdeg, 0);
    EXPECT_EQ(junction_speed(1000, j, c.in, c.out, 1000), 0u);
  }
}

// ---- properties -----------------------------------------------------------------------------

RC_GTEST_PROP(LookaheadProps, Symmetric, ()) {
  const Direction a = *gen_direction();
  const Direction b = *gen_direction();
  RC_ASSERT(same(junction(a, b), junction(b, a)));
}

RC_GTEST_PROP(LookaheadProps, ScalingInvariant, ()) {
  const Direction a = *gen_direction();
  const Direction b = *gen_direction();
  const auto ka = *rc::gen::inRange<int64_t>(1, 1000);
  const auto kb = *rc::gen::inRange<int64_t>(1, 1000);
  const Direction sa = xy(a.x * ka, a.y * ka);
  const Direction sb = xy(b.x * kb, b.y * kb);
  RC_PRE(sa.has_direction() && sb.has_direction());  // still within kComponentMax
  // cross and dot both scale by ka * kb, so |cross| : dot and everything after it is unchanged.
  RC_ASSERT(same(junction(a, b), junction(sa, sb)));
}

RC_GTEST_PROP(LookaheadProps, Rotation90Invariant, ()) {
  const Direction a = *gen_direction();
  const Direction b = *gen_direction();
  const Direction ra = xy(-a.y, a.x);
  const Direction rb = xy(-b.y, b.x);
  RC_ASSERT(same(junction(a, b), junction(ra, rb)));
}

RC_GTEST_PROP(LookaheadProps, TurnWithin1mdegOfReference, ()) {
  const Direction a = *gen_direction();
  const Direction b = *gen_direction();
  const Junction j = junction(a, b);
  const double t = ref::ref_turn_deg(dbl(a.x), dbl(a.y), dbl(b.x), dbl(b.y)) * 1000.0;
  RC_ASSERT(j.turn_mdeg >= 0);
  RC_ASSERT(j.turn_mdeg <= 180'000);
  // 1 mdeg plus 1e-6 for the double reference (atan2 difference of two large vectors).
  RC_ASSERT(std::abs(j.turn_mdeg - t) <= 1.0 + 1e-6);
  // The kind follows the exact sign tests, the factor the law on the reported turn.
  const int64_t cross = a.x * b.y - a.y * b.x;
  const int64_t dot = a.x * b.x + a.y * b.y;
  if (cross == 0 && dot > 0) {
    RC_ASSERT(j.kind == JunctionKind::Straight);
    RC_ASSERT(j.factor_permille == 1000);
  } else if (dot > 0) {
    RC_ASSERT(j.kind == JunctionKind::Corner);
    RC_ASSERT(j.factor_permille <= 999);
    RC_ASSERT(std::abs(j.factor_permille - 1000.0 * ref::ref_factor(t / 1000.0)) <= 1.0 + 1e-6);
  } else {
    RC_ASSERT(j.kind == JunctionKind::Stop);
    RC_ASSERT(j.factor_permille == 0);
  }
}

// A sharper turn never gets a higher factor.
RC_GTEST_PROP(LookaheadProps, FactorMonotoneInTurn, ()) {
  const Junction j = junction(*gen_direction(), *gen_direction());
  const Junction k = junction(*gen_direction(), *gen_direction());
  if (j.turn_mdeg <= k.turn_mdeg) {
    RC_ASSERT(j.factor_permille >= k.factor_permille);
  } else {
    RC_ASSERT(j.factor_permille <= k.factor_permille);
  }
}

// ---- junction speed -------------------------------------------------------------------------

// v_max = 1000 steps/s (50 mm/s at 20 steps/mm, seed-003.md §2.5), v_jump = 100 steps/s.
TEST(LookaheadSpeed, TypedCases) {
  struct Case {
    int64_t x1, y1, x2, y2;
    uint32_t speed;
  };
  for (const Case c : {
           Case{3, 4, 6, 8, 1000},              // straight: no jump
           Case{1, 0, 1, 1, 141},               // 45 deg: factor 500, cap 100 / sin 45 = 141.42
           Case{1, 1, 0, 1, 141},               // 45 deg: the X axis jumps by 0.7071
           Case{1, 0, 984'808, 173'648, 575},   // 10 deg: factor 889, cap 100 / sin 10 = 575.88
           Case{1, 0, 0, 1, 0},                 // 90 deg: stop
           Case{1, 0, -1, 0, 0},                // reversal
       }) {
    SCOPED_TRACE(testing::Message() << c.x1 << "," << c.y1 << " -> " << c.x2 << "," << c.y2);
    const Direction a = xy(c.x1, c.y1);
    const Direction b = xy(c.x2, c.y2);
    EXPECT_EQ(junction_speed(1000, junction(a, b), a, b, 100), c.speed);
  }
  // The factor limits when the axes allow more: 45 deg, v_jump 1000 -> cap 1414, factor 500.
  const Direction a = xy(1, 0);
  const Direction b = xy(1, 1);
  EXPECT_EQ(junction_speed(1000, junction(a, b), a, b, 1000), 500u);
  // v_jump = 0: any corner is a full stop, a straight junction still runs at v_max.
  EXPECT_EQ(junction_speed(1000, junction(a, b), a, b, 0), 0u);
  EXPECT_EQ(junction_speed(1000, junction(a, a), a, a, 0), 1000u);
  // Extreme values: no overflow.
  constexpr uint32_t kU32 = std::numeric_limits<uint32_t>::max();
  EXPECT_EQ(junction_speed(kU32, junction(a, a), a, a, kU32), kU32);
  EXPECT_EQ(junction_speed(kU32, junction(a, b), a, b, kU32), kU32 / 2);  // factor 500 floors
}

TEST(LookaheadSpeed, ForgedJunctionGivesZero) {
  const Direction a = xy(1, 0);
  const Direction b = xy(1, 1);
  Junction j = junction(a, b);
  j.factor_permille = 1001;
  EXPECT_EQ(junction_speed(1000, j, a, b, 100), 0u);
  EXPECT_EQ(junction_speed(1000, Junction{90'000, 0, JunctionKind::Stop}, a, b, 100), 0u);
}

// Never above the real min(v_max * factor, v_jump / max|du|) (the cap is conservative: the
// real per-axis jump at the returned speed is <= v_jump), and at most the documented margin
// below: cap >= v_jump * 2^30 / (D + 8) - 1, D = max|du| * 2^30 (docs/lookahead.md).
RC_GTEST_PROP(LookaheadSpeed, ConservativeAndTight, ()) {
  const Direction a = *gen_direction();
  const Direction b = *gen_direction();
  const auto v_max = *rc::gen::arbitrary<uint32_t>();
  const auto v_jump = *rc::gen::arbitrary<uint32_t>();
  const Junction j = junction(a, b);
  const uint32_t v = junction_speed(v_max, j, a, b, v_jump);
  const double by_factor = std::floor(static_cast<double>(v_max) * j.factor_permille / 1000.0);
  RC_ASSERT(static_cast<double>(v) <= by_factor);
  if (j.kind == JunctionKind::Stop) {
    RC_ASSERT(v == 0u);
    return;
  }
  if (j.kind == JunctionKind::Straight) {
    RC_ASSERT(v == v_max);
    return;
  }
  const double du = ref::ref_max_du(dbl(a.x), dbl(a.y), dbl(b.x), dbl(b.y));
  RC_ASSERT(static_cast<double>(v) * du <= static_cast<double>(v_jump) * (1 + 1e-12));
  {
    const double q30 = 1073741824.0;
    const double lower = static_cast<double>(v_jump) * q30 / (du * q30 + 8) - 1;
    RC_ASSERT(static_cast<double>(v) >= std::min(by_factor, lower) - 1e-6);
  }
}
