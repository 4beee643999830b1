// Integer atan2 in millidegrees (core/xy/lookahead/angle.hpp) against std::atan2.
// E = 0.6 mdeg is the bound derived in docs/lookahead.md "Angle" (typed here, not read from the
// code). The dense grid is exhaustive over |x|, |y| <= 500 (1002001 points);
// random inputs cover the full int64 range and the int32 range.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>

#include "core/xy/lookahead/angle.hpp"

using ap::xy_lookahead::Angle;
using ap::xy_lookahead::AngleStatus;
using ap::xy_lookahead::atan2_mdeg;

namespace {

constexpr double kBoundMdeg = 0.6;  // docs/lookahead.md "Angle": E = 0.576 mdeg, stated as 0.6

// std::atan2 in mdeg; doubles of int64 inputs are within 2^-53 relative (angle error < 1e-11 mdeg).
double ref_mdeg(int64_t y, int64_t x) {
  return std::atan2(static_cast<double>(y), static_cast<double>(x)) * 180'000.0 / std::numbers::pi;
}

// Difference wrapped into [-180000, 180000): -180000 and 180000 are the same direction.
double wrapped_error(int32_t got, double ref) {
  double d = static_cast<double>(got) - ref;
  while (d >= 180'000.0) {
    d -= 360'000.0;
  }
  while (d < -180'000.0) {
    d += 360'000.0;
  }
  return std::abs(d);
}

int32_t wrap_mdeg(int64_t a) {
  while (a > 180'000) {
    a -= 360'000;
  }
  while (a <= -180'000) {
    a += 360'000;
  }
  return static_cast<int32_t>(a);
}

}  // namespace

TEST(LookaheadAngle, AxesAndDiagonalsAreExact) {
  struct Case {
    int64_t y, x;
    int32_t mdeg;
  };
  for (const Case c : {Case{0, 1, 0}, Case{0, 5000, 0}, Case{1, 0, 90'000}, Case{2000, 0, 90'000},
                       Case{0, -1, 180'000}, Case{0, -4000, 180'000}, Case{-1, 0, -90'000}, Case{-2000, 0, -90'000},
                       Case{1, 1, 45'000}, Case{4000, 4000, 45'000}, Case{1, -1, 135'000}, Case{-1, -1, -135'000},
                       Case{-3, 3, -45'000}, Case{0, std::numeric_limits<int64_t>::min(), 180'000},
                       Case{std::numeric_limits<int64_t>::max(), 0, 90'000}}) {
    SCOPED_TRACE(testing::Message() << "y=" << c.y << " x=" << c.x);
    const Angle a = atan2_mdeg(c.y, c.x);
    EXPECT_EQ(a.status, AngleStatus::Ok);
    EXPECT_EQ(a.mdeg, c.mdeg);
  }
}

TEST(LookaheadAngle, ZeroVectorHasNoDirection) {
  const Angle a = atan2_mdeg(0, 0);
  EXPECT_EQ(a.status, AngleStatus::NoDirection);
  EXPECT_FALSE(a.ok());
}

// Just below the -X axis the angle is -179.99999.. deg; rounded it is the -X axis, which the
// range (-180000, 180000] names 180000.
TEST(LookaheadAngle, JustBelowMinusXIsReportedAs180) {
  const Angle a = atan2_mdeg(-1, -(int64_t{1} << 40));
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a.mdeg, 180'000);
  const Angle b = atan2_mdeg(-1, -1000);  // -179.94270 deg: far enough to stay negative
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b.mdeg, -179'943);
}

TEST(LookaheadAngle, TableMatchesAtan) {
  const auto& t = ap::xy_lookahead::detail::kAtanTableUdeg;
  for (size_t i = 0; i < t.size(); ++i) {
    const double udeg = std::atan(static_cast<double>(i) / 256.0) * 180e6 / std::numbers::pi;
    EXPECT_LE(std::abs(static_cast<double>(t[i]) - udeg), 0.5) << "i=" << i;
  }
}

TEST(LookaheadAngle, DenseGridWithinBound) {
  constexpr int64_t kR = 500;  // exhaustive over [-500, 500]^2 minus (0, 0)
  double worst = 0;
  int64_t wx = 0;
  int64_t wy = 0;
  for (int64_t y = -kR; y <= kR; ++y) {
    for (int64_t x = -kR; x <= kR; ++x) {
      if (x == 0 && y == 0) {
        continue;
      }
      const Angle a = atan2_mdeg(y, x);
      const double e = wrapped_error(a.mdeg, ref_mdeg(y, x));
      if (!a.ok() || a.mdeg <= -180'000 || a.mdeg > 180'000 || e > worst) {
        worst = a.ok() && a.mdeg > -180'000 && a.mdeg <= 180'000 ? e : 1e9;
        wx = x;
        wy = y;
      }
    }
  }
  std::printf("atan2_mdeg grid [-%lld, %lld]^2: max error %.4f mdeg at (x=%lld, y=%lld)\n",
              static_cast<long long>(kR), static_cast<long long>(kR), worst, static_cast<long long>(wx),
              static_cast<long long>(wy));
  EXPECT_LE(worst, kBoundMdeg);
}

RC_GTEST_PROP(LookaheadAngle, RandomInt64WithinBound, (int64_t y, int64_t x)) {
  RC_PRE(x != 0 || y != 0);
  const Angle a = atan2_mdeg(y, x);
  RC_ASSERT(a.ok());
  RC_ASSERT(a.mdeg > -180'000);
  RC_ASSERT(a.mdeg <= 180'000);
  RC_ASSERT(wrapped_error(a.mdeg, ref_mdeg(y, x)) <= kBoundMdeg);
}

RC_GTEST_PROP(LookaheadAngle, RandomInt32WithinBound, (int32_t y, int32_t x)) {
  RC_PRE(x != 0 || y != 0);
  const Angle a = atan2_mdeg(y, x);
  RC_ASSERT(a.ok());
  RC_ASSERT(wrapped_error(a.mdeg, ref_mdeg(y, x)) <= kBoundMdeg);
}

// Small steps around the table knots (i/256): interpolation and knot rounding.
TEST(LookaheadAngle, NearTableKnotsWithinBound) {
  constexpr int64_t kX = int64_t{1} << 20;
  double worst = 0;
  for (int64_t i = 0; i <= 256; ++i) {
    for (int64_t d = -3; d <= 3; ++d) {
      const int64_t y = i * (kX / 256) + d * 1365;  // knot and 1/768-step either side
      if (y < 0 || y > kX) {
        continue;
      }
      const Angle a = atan2_mdeg(y, kX);
      worst = std::max(worst, wrapped_error(a.mdeg, ref_mdeg(y, kX)));
    }
  }
  EXPECT_LE(worst, kBoundMdeg);
}

// Rotating (x, y) by +90 deg gives (-y, x): the angle grows by exactly 90000 (mod 360000).
RC_GTEST_PROP(LookaheadAngle, RotationBy90IsExact, (int32_t y, int32_t x)) {
  RC_PRE(x != 0 || y != 0);
  const Angle a = atan2_mdeg(y, x);
  const Angle r = atan2_mdeg(x, -int64_t{y});
  RC_ASSERT(r.mdeg == wrap_mdeg(int64_t{a.mdeg} + 90'000));
}

// Mirroring in the X axis negates the angle (180000 stays 180000).
RC_GTEST_PROP(LookaheadAngle, MirrorIsExact, (int32_t y, int32_t x)) {
  RC_PRE(x != 0 || y != 0);
  const Angle a = atan2_mdeg(y, x);
  const Angle m = atan2_mdeg(-int64_t{y}, x);
  RC_ASSERT(m.mdeg == wrap_mdeg(-int64_t{a.mdeg}));
}

RC_GTEST_PROP(LookaheadAngle, ScalingIsExact, (int32_t y, int32_t x)) {
  RC_PRE(x != 0 || y != 0);
  const auto k = *rc::gen::inRange<int64_t>(1, int64_t{1} << 31);
  RC_ASSERT(atan2_mdeg(k * y, k * x).mdeg == atan2_mdeg(y, x).mdeg);
}
