// The joystick mapping (core/unit3_joystick) at the codes seed 001 §3.6 and §10.4 name, with
// the values eq. 6 and 7 give for them worked out by hand.
#include <gtest/gtest.h>

#include <cstdint>

#include "core/unit3_joystick/joystick.hpp"

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

}  // namespace
