// Arc full circles, exhaustively (docs/interpolation.md "Arc"): radial error < 1/2, 8-connected
// moves turning the right way, once around, back exactly at the start, the guard never reached.
// Bounds: every start point with R <= 48 and every first-octant start point with R <= 150.
#include <gtest/gtest.h>

#include <cstdio>

#include "arc_harness.hpp"

namespace {

using namespace ap::interp_test;  // NOLINT(google-build-using-namespace): the harness

// Exhaustive: every integer start point with R <= 48 (7 237 points), full circles both ways.
TEST(InterpArc, ExhaustiveFullCirclesEveryStartUpTo48) {
  constexpr int32_t kB = 48;
  for (int32_t x = -kB; x <= kB; ++x) {
    for (int32_t y = -kB; y <= kB; ++y) {
      if ((x == 0 && y == 0) || x * x + y * y > kB * kB) continue;
      for (const Turn turn : {Turn::Cw, Turn::Ccw}) {
        const std::string why = check_full_circle({x, y}, turn);
        ASSERT_TRUE(why.empty()) << why << " from (" << x << ", " << y << ") " << (turn == Turn::Cw ? "CW" : "CCW");
      }
    }
  }
}

// Every radius: every squared radius R2 <= 150^2 that has integer points, from each of its
// points in the first octant (0 <= y <= x), full circles both ways (checks of trace()).
// (R <= 150 keeps this under ~1.5 s in a Debug build; the bound is R^3.)
TEST(InterpArc, EveryRadiusUpTo150FromTheFirstOctant) {
  constexpr int32_t kB = 150;
  int circles = 0;
  for (int32_t x = 1; x <= kB; ++x) {
    for (int32_t y = 0; y <= x; ++y) {
      if (x * x + y * y > kB * kB) continue;
      for (const Turn turn : {Turn::Cw, Turn::Ccw}) {
        const Trace t = trace({x, y}, {x, y}, turn);
        ASSERT_TRUE(t.failure.empty()) << t.failure << " from (" << x << ", " << y << ")";
        ASSERT_EQ(t.circle_moves, static_cast<int64_t>(t.points.size()) - 1) << x << " " << y;
        ++circles;
      }
    }
  }
  std::printf("%d full circles\n", circles);
}

}  // namespace
