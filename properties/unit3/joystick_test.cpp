// The joystick mapping (core/unit3/joystick) at the codes seed 001 §3.6 and §10.4 name, with
// the values eq. 6 and 7 give for them worked out by hand.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "core/unit3/joystick/joystick.hpp"

namespace {

namespace j = ap::unit3_joystick;
using D = j::Deflection;

TEST(Unit3Joystick, ThesisCodes) {
  // Below the dead band, eq. 6: index = (512 - ADC) / 16, moving down.
  EXPECT_EQ(j::deflection(499), (D{-1, 0}));   // 13 / 16
  EXPECT_EQ(j::deflection(497), (D{-1, 0}));   // 15 / 16
  EXPECT_EQ(j::deflection(496), (D{-1, 1}));   // 16 / 16
  EXPECT_EQ(j::deflection(481), (D{-1, 1}));   // 31 / 16
  EXPECT_EQ(j::deflection(17), (D{-1, 30}));   // 495 / 16
  EXPECT_EQ(j::deflection(16), (D{-1, 31}));   // 496 / 16
  EXPECT_EQ(j::deflection(1), (D{-1, 31}));    // 511 / 16
  EXPECT_EQ(j::deflection(0), (D{-1, 31}));    // 512 / 16 = 32: one past the table, clamped
  // The dead band 500..524, both ends included (docs/unit3.md).
  EXPECT_EQ(j::deflection(500), (D{}));
  EXPECT_EQ(j::deflection(512), (D{}));
  EXPECT_EQ(j::deflection(524), (D{}));
  // Above, eq. 7: index = (ADC - 524) / 16, moving up.
  EXPECT_EQ(j::deflection(525), (D{1, 0}));
  EXPECT_EQ(j::deflection(539), (D{1, 0}));    // 15 / 16
  EXPECT_EQ(j::deflection(540), (D{1, 1}));    // 16 / 16
  EXPECT_EQ(j::deflection(1019), (D{1, 30}));  // 495 / 16
  EXPECT_EQ(j::deflection(1020), (D{1, 31}));  // 496 / 16
  EXPECT_EQ(j::deflection(1023), (D{1, 31}));  // 499 / 16
  EXPECT_EQ(j::deflection(4000), (D{1, 31}));  // not a 10-bit code: taken as 1023
}

// How many ADC codes give each index, counted over all 1024 codes. Eq. 6 and 7 on the thesis's
// intervals (001_*.txt:1138-1168) give index 0 to the four codes 497..500 below and the sixteen
// 524..539 above; docs/unit3.md decides that both ends of the dead band, 500 and 524, stop the
// axis, so a moving axis has index 0 for 3 codes below (497..499) and 15 above (525..539), then
// 16 codes per index; index 31 takes 0..16 below (17, ADC 0 clamped into it) and 1020..1023
// above (4).
TEST(Unit3Joystick, CodesPerIndexAsDocumented) {
  std::array<int, 32> below{}, above{};
  int stop = 0;
  for (std::uint16_t adc = 0; adc <= 1023; ++adc) {
    const D d = j::deflection(adc);
    if (d.dir == 0) {
      ++stop;
    } else {
      ASSERT_LT(d.index, 32);
      (d.dir < 0 ? below : above)[d.index]++;
    }
  }
  EXPECT_EQ(stop, 25);  // 500..524
  EXPECT_EQ(below[0], 3);
  EXPECT_EQ(above[0], 15);
  for (int i = 1; i <= 30; ++i) {
    EXPECT_EQ(below[static_cast<std::size_t>(i)], 16) << i;
    EXPECT_EQ(above[static_cast<std::size_t>(i)], 16) << i;
  }
  EXPECT_EQ(below[31], 17);
  EXPECT_EQ(above[31], 4);
}

}  // namespace
