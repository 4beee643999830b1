// Bresenham (core/xy/interp/line.hpp) against the thesis's DDA and its all-octant Bresenham loop
// (models/xy/dda, seed-003.md §3.1, §3.2, §3.6, §11.6). docs/interpolation.md "DDA".
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "core/xy/interp/line.hpp"
#include "models/xy/dda/dda.hpp"

namespace {

namespace xy_dda = ap::model::xy_dda;
using ap::xy_interp::Line;

std::vector<Eigen::Vector3i> bresenham(int32_t dx, int32_t dy, int32_t dz) {
  Line l{{dx, dy, dz}};
  std::vector<Eigen::Vector3i> pts;
  pts.emplace_back(0, 0, 0);
  while (!l.done()) {
    l.next();
    const auto p = l.position();
    pts.emplace_back(p[0], p[1], p[2]);
  }
  return pts;
}

struct Comparison {
  int ties = 0;         // points where some ideal minor coordinate is exactly half-way
  int ties_differ = 0;  // ... where the DDA's rounded point differs from Bresenham's
  bool ok = true;
};

// The characterisation (docs/interpolation.md "DDA"): equal at every point whose ideal position
// has no exact .5 tie; at a tie the DDA equals Bresenham or is exactly one step closer to the
// start on the tied axis (its float sum fell just below the half).
void compare(const Eigen::Vector3i& d, Comparison& c) {
  const auto b = bresenham(d[0], d[1], d[2]);
  const auto f = xy_dda::rounded_line({0, 0, 0}, d);
  if (b.size() != f.size()) {
    c.ok = false;
    return;
  }
  const int64_t n = d.cwiseAbs().maxCoeff();
  for (std::size_t k = 0; k < b.size(); ++k) {
    bool tie_here = false, differ = false;
    for (int i = 0; i < 3; ++i) {
      const int64_t a = std::abs(d[i]);
      const bool tie = n > 0 && (2 * static_cast<int64_t>(k) * a) % (2 * n) == n;
      tie_here = tie_here || tie;
      if (b[k][i] == f[k][i]) continue;
      differ = true;
      const int s = d[i] > 0 ? 1 : -1;
      if (!tie || f[k][i] != b[k][i] - s) c.ok = false;
    }
    c.ties += tie_here ? 1 : 0;
    c.ties_differ += differ ? 1 : 0;
  }
}

TEST(InterpDda, BresenhamEqualsTheThesisLoopExhaustively) {
  // seed §3.2's loop; every delta with |dx|, |dy| <= 64.
  for (int dx = -64; dx <= 64; ++dx) {
    for (int dy = -64; dy <= 64; ++dy) {
      const auto t = xy_dda::thesis_bresenham({0, 0}, {dx, dy});
      const auto b = bresenham(dx, dy, 0);
      ASSERT_EQ(t.size(), b.size()) << dx << " " << dy;
      for (std::size_t k = 0; k < t.size(); ++k) {
        ASSERT_TRUE(t[k][0] == b[k][0] && t[k][1] == b[k][1]) << dx << " " << dy << " point " << k;
      }
    }
  }
}

TEST(InterpDda, DdaEqualsBresenhamExceptAtTiesExhaustively) {
  Comparison c;
  for (int dx = -64; dx <= 64; ++dx) {
    for (int dy = -64; dy <= 64; ++dy) compare({dx, dy, 0}, c);
  }
  EXPECT_TRUE(c.ok);
  // Counted over this range (docs/interpolation.md); the DDA's float drift makes some ties differ.
  EXPECT_GT(c.ties, 0);
  EXPECT_GT(c.ties_differ, 0);
  EXPECT_LT(c.ties_differ, c.ties);
  std::printf("ties %d, of which the DDA differs at %d\n", c.ties, c.ties_differ);
}

RC_GTEST_PROP(InterpDda, Random3DDdaEqualsBresenhamExceptAtTies, ()) {
  Comparison c;
  compare({*rc::gen::inRange(-3000, 3001), *rc::gen::inRange(-3000, 3001), *rc::gen::inRange(-3000, 3001)}, c);
  RC_ASSERT(c.ok);
}

TEST(InterpDda, ExactTieWhereTheDdaIsOneStepBehind) {
  // (12,1): ideal y at x = 6 is 6/12 = 1/2. Six additions of 1/12 in doubles give
  // 0.49999999999999994 < 0.5, so the DDA rounds to 0; Bresenham's tie rule gives 1.
  double sum = 0;
  for (int i = 0; i < 6; ++i) sum += 1.0 / 12;
  EXPECT_LT(sum, 0.5);
  const auto f = xy_dda::rounded_line({0, 0, 0}, {12, 1, 0});
  const auto b = bresenham(12, 1, 0);
  EXPECT_EQ(f[6], Eigen::Vector3i(6, 0, 0));
  EXPECT_EQ(b[6], Eigen::Vector3i(6, 1, 0));
  // (4,1): 0.25 + 0.25 = 0.5 exactly: both round the tie up.
  EXPECT_EQ(xy_dda::rounded_line({0, 0, 0}, {4, 1, 0})[2], Eigen::Vector3i(2, 1, 0));
  EXPECT_EQ(bresenham(4, 1, 0)[2], Eigen::Vector3i(2, 1, 0));
}

TEST(InterpDda, ThesisN01IsIdenticalInBoth) {
  // seed §3.6/§9: the MIL plots of Bresenham and DDA were "completely identical" for N01.
  const auto f = xy_dda::rounded_line({0, 0, 0}, {4000, 4000, 0});
  const auto b = bresenham(4000, 4000, 0);
  ASSERT_EQ(f.size(), 4001U);
  EXPECT_EQ(f, b);
}

TEST(InterpDda, ZeroLengthMoveHasNoNaN) {
  // seed §11.6: the thesis's DDA computes dx/steps with steps = 0 for Z-only moves (N02, N07).
  const auto pts = xy_dda::line({4000, 6000, 0}, {4000, 6000, 0});
  ASSERT_EQ(pts.size(), 1U);
  EXPECT_TRUE(pts[0].allFinite());
  EXPECT_EQ(pts[0], (Eigen::Vector3d(4000, 6000, 0)));
  const auto z_only = xy_dda::line({4000, 4000, 0}, {4000, 4000, 10});
  ASSERT_EQ(z_only.size(), 11U);
  EXPECT_TRUE(z_only.back().allFinite());
  EXPECT_EQ(Line({0, 0, 0}).moves(), 0U);
}

}  // namespace
