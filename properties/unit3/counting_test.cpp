// Step counting (core/unit3/axis) against seed 001 §2.3, §3.3-3.4 and docs/unit3.md
// "Counting"; expected values worked out by hand from those texts.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "core/unit3/axis/counting.hpp"

namespace {

namespace u = ap::unit3_axis;

TEST(Unit3Counting, ThesisExamples) {
  // Y000000000016000; in full step: 500 full steps = 16000 counts.
  const auto full = u::plan_move(0, 1, 16000, 0);
  EXPECT_EQ(full.error, u::Error::None);
  EXPECT_EQ(full.pulses, 500U);
  EXPECT_EQ(full.target, 16000);
  // Y000000000000500; at 1/32: 500 microsteps = 500 counts.
  const auto micro = u::plan_move(0, 1, 500, 5);
  EXPECT_EQ(micro.pulses, 500U);
  EXPECT_EQ(micro.target, 500);
  // Down from 1000 by 160 counts at 1/8 step (4 counts per pulse): 40 pulses.
  const auto down = u::plan_move(1000, -1, 160, 3);
  EXPECT_EQ(down.pulses, 40U);
  EXPECT_EQ(down.target, 840);
}

TEST(Unit3Counting, ModesAndPins) {
  // Tab. 7: MODE2..0 = the digit's binary value; counts per pulse 32, 16, 8, 4, 2, 1.
  const std::uint32_t per[] = {32, 16, 8, 4, 2, 1};
  for (std::uint8_t d = 0; d < u::kModes; ++d) {
    EXPECT_EQ(u::counts_per_pulse(d), per[d]);
    EXPECT_EQ(u::kModePins[d], (u::ModePins{(d & 4) != 0, (d & 2) != 0, (d & 1) != 0}));
  }
}

TEST(Unit3Counting, RefusalsChangeNothing) {
  EXPECT_EQ(u::plan_move(7, 1, 500, 0).error, u::Error::NotMultiple);  // 500 / 32 = 15.625 pulses
  EXPECT_EQ(u::plan_move(7, 1, 500, 0).target, 7);
  EXPECT_EQ(u::plan_move(7, 1, 32, 6).error, u::Error::BadMode);
  EXPECT_EQ(u::plan_move(7, 1, 1'000'000'000'000'000ULL, 5).error, u::Error::TooFar);
  EXPECT_EQ(u::plan_move(999'999'999'999'999'000LL, 1, 1000, 5).error, u::Error::CounterRange);
  EXPECT_EQ(u::plan_move(999'999'999'999'999'000LL, 1, 999, 5).target, 999'999'999'999'999'999LL);
  EXPECT_EQ(u::plan_move(-999'999'999'999'999'000LL, -1, 1000, 5).error, u::Error::CounterRange);
}

TEST(Unit3Counting, PositionInMicrometres) {
  // Eq. 5: position = count / 6400 * pitch.
  EXPECT_EQ(u::position_um(16000, 0), 1000);   // M2, 0.4 mm/rev [T]: 2.5 rev = 1 mm
  EXPECT_EQ(u::position_um(6400, 4), 1000);    // M6, 1 mm/rev [T]; at index 4 [D]
  EXPECT_EQ(u::position_um(-6400, 6), -1500);  // M10, 1.5 mm/rev [D]
  EXPECT_EQ(u::position_um(8, 0), 1);          // 0.5 µm: half away from zero
  EXPECT_EQ(u::position_um(-8, 0), -1);
  EXPECT_EQ(u::position_um(7, 0), 0);          // 0.4375 µm
  EXPECT_EQ(u::position_um(u::kMaxCounter, 6), 234'375'000'000'000'000LL);  // (10^18 - 1) * 1500 / 6400 = ...999.77
}

// What the thesis states of the thread table, and only that (docs/unit3.md "Counting"): the
// pitches of M2 (0.4 mm) and M6 (1 mm), 001_*.txt:1037-1039; index 0 = M2 and index 6 = M10,
// 001_*.txt:1326-1328. M6's index and every other pitch are decisions.
TEST(Unit3Counting, ThreadTableMarksOnlyWhatTheThesisStates) {
  for (std::size_t i = 0; i < u::kThreads; ++i) {
    const std::string name = u::kThreadTable[i].name;
    EXPECT_EQ(u::kThreadTable[i].pitch_from_thesis, name == "M2" || name == "M6") << name;
    EXPECT_EQ(u::kThreadTable[i].index_from_thesis, i == 0 || i == 6) << name;
  }
  EXPECT_EQ(std::string(u::kThreadTable[0].name), "M2");
  EXPECT_EQ(u::kThreadTable[0].pitch_um, 400U);
  EXPECT_EQ(std::string(u::kThreadTable[6].name), "M10");
  EXPECT_EQ(u::kThreadTable[4].pitch_um, 1000U);  // M6's pitch [T], wherever M6 sits
  EXPECT_EQ(std::string(u::kThreadTable[4].name), "M6");
}

}  // namespace
