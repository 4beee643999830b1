// The unit3 panel's mm-to-count conversion (pc/unit3/panel/conversion.hpp) against seed-001.md
// §7: the move reaches the achievable position nearest to the one typed, in whole steps of the
// axis's mode. Pitches as docs/unit3.md decides them, written out here.
#include "pc/unit3/panel/conversion.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>

namespace {

using ap::unit3_panel::to_counts;

// µm per revolution, digits 0..6: M2 M3 M4 M5 M6 M8 M10 (docs/unit3.md "Threads").
constexpr std::array<std::int64_t, 7> kPitchUm{400, 500, 700, 800, 1000, 1250, 1500};

TEST(Unit3PanelConversion, TheSeedsWorkedExamples) {
  // M2 at 1/32, +1 mm: 2.5 revolutions, 16000 microsteps (seed-001.md §7).
  const auto a = to_counts(1000, 5, 0);
  ASSERT_TRUE(a.ok);
  EXPECT_EQ(a.count, 16000U);
  EXPECT_EQ(a.sign, 1);
  EXPECT_EQ(a.achieved_um, 1000);
  // M6 at full step, 1 mm: 200 steps, 6400 counts.
  const auto b = to_counts(-1000, 0, 4);
  ASSERT_TRUE(b.ok);
  EXPECT_EQ(b.steps, 200U);
  EXPECT_EQ(b.count, 6400U);
  EXPECT_EQ(b.sign, -1);
  EXPECT_EQ(b.achieved_um, -1000);
}

TEST(Unit3PanelConversion, OutOfRangeIsRefusedWithItsReason) {
  EXPECT_FALSE(to_counts(1000, 6, 0).ok);
  EXPECT_FALSE(to_counts(1000, 0, 7).ok);
  EXPECT_FALSE(to_counts(1'000'000, 0, 0).ok);
  EXPECT_FALSE(to_counts(-1'000'000, 0, 0).ok);
  EXPECT_NE(to_counts(1000, 6, 0).error.find("mode"), std::string::npos);
}

// The nearest whole step: |steps * L - d| <= L / 2 for a step of L = pitch / (200 * 2^mode)
// (in units of 1/(200 * 2^mode) µm, to stay in integers), and the count is whole pulses.
RC_GTEST_PROP(Unit3PanelConversionProps, TheMoveIsTheNearestWholeStep, ()) {
  const auto mode = *rc::gen::inRange<std::uint8_t>(0, 6);
  const auto thread = *rc::gen::inRange<std::uint8_t>(0, 7);
  const auto um = *rc::gen::inRange<std::int64_t>(-999'999, 1'000'000);
  const auto c = to_counts(um, mode, thread);
  RC_ASSERT(c.ok);
  const std::int64_t per_rev = 200LL << mode;
  const std::int64_t p = kPitchUm[thread];
  const std::int64_t d = std::llabs(um) * per_rev;  // |d| in 1/per_rev µm
  const auto steps = static_cast<std::int64_t>(c.steps);
  RC_ASSERT(2 * std::llabs(steps * p - d) <= p);
  RC_ASSERT(c.count == c.steps * (32U >> mode));
  RC_ASSERT(c.sign == (um < 0 ? -1 : 1));
}

}  // namespace
