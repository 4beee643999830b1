// Edge values of the axis helpers (core/xy/axis units, start position, step timer, invariants):
// every documented bound of the mechanics, the inward rounding at both travel limits, the
// representable-position limit, encoder and saved-counter fallbacks, and the typed answers to
// out-of-range input (a corrupted state or enum byte is reported, never indexed).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "core/xy/axis/axis.hpp"
#include "core/xy/axis/position.hpp"
#include "core/xy/axis/step_timer.hpp"
#include "core/xy/axis/units.hpp"

using namespace ap::xy_axis;

TEST(AxisEdges, MechanicsBoundsAreInclusive) {
  const Mechanics ok_lo{1, 1, 1};
  const Mechanics ok_hi{100'000, 1000, 256};
  EXPECT_TRUE(mechanics_valid(ok_lo));
  EXPECT_TRUE(mechanics_valid(ok_hi));
  for (const Mechanics bad : {Mechanics{0, 200, 16}, Mechanics{100'001, 200, 16}, Mechanics{2000, 0, 16},
                              Mechanics{2000, 1001, 16}, Mechanics{2000, 200, 0}, Mechanics{2000, 200, 257}}) {
    SCOPED_TRACE(testing::Message() << bad.pitch_um << " " << bad.steps_per_rev << " " << bad.microsteps);
    EXPECT_FALSE(mechanics_valid(bad));
    EXPECT_EQ(um_to_usteps(1000, bad, Round::Nearest).error, Error::BadConfig);
    EXPECT_EQ(speed_to_usteps(1000, bad).error, Error::BadConfig);
    EXPECT_EQ(limits_to_usteps(0, 1000, bad).error, Error::BadConfig);
    EXPECT_EQ(target_to_usteps(10, 0, 1000, bad).error, Error::BadConfig);
  }
}

TEST(AxisEdges, TravelLimitErrors) {
  const Mechanics m{};  // 1.6 usteps/um
  // Lower limit beyond the representable range: its error is reported.
  const UstepLimits lo_bad = limits_to_usteps(-1'000'000'000, 0, m);
  EXPECT_EQ(lo_bad.error, Error::OutOfLimits);
  EXPECT_EQ(lo_bad.min, 0);
  EXPECT_EQ(lo_bad.max, 0);
  // Upper limit beyond it, lower fine.
  EXPECT_EQ(limits_to_usteps(0, 1'000'000'000, m).error, Error::OutOfLimits);
  // An interval that rounds inward to nothing (1 um -> [2, 1] usteps) is a configuration error.
  EXPECT_EQ(limits_to_usteps(1, 1, m).error, Error::BadConfig);
  EXPECT_EQ(target_to_usteps(1, 1, 1, m).error, Error::BadConfig);
  // Outside the um limits comes first.
  EXPECT_EQ(target_to_usteps(2, 0, 1, m).error, Error::OutOfLimits);
  EXPECT_EQ(target_to_usteps(-1, 0, 1, m).error, Error::OutOfLimits);
}

// A target exactly on a soft limit rounds to nearest, which can fall outside the limits
// rounded inward; it is pulled back onto them, never past.
TEST(AxisEdges, TargetOnALimitIsPulledInward) {
  const Mechanics m{};  // 1.6 usteps/um
  // min 4 um = 6.4 usteps: the limit rounds up to 7, the target to nearest 6 -> 7.
  const UstepLimits lim_lo = limits_to_usteps(4, 1000, m);
  ASSERT_EQ(lim_lo.error, Error::None);
  EXPECT_EQ(lim_lo.min, 7);
  const Converted at_min = target_to_usteps(4, 4, 1000, m);
  ASSERT_EQ(at_min.error, Error::None);
  EXPECT_EQ(at_min.value, 7);
  // max 3 um = 4.8 usteps: the limit rounds down to 4, the target to nearest 5 -> 4.
  const UstepLimits lim_hi = limits_to_usteps(-1000, 3, m);
  ASSERT_EQ(lim_hi.error, Error::None);
  EXPECT_EQ(lim_hi.max, 4);
  const Converted at_max = target_to_usteps(3, -1000, 3, m);
  ASSERT_EQ(at_max.error, Error::None);
  EXPECT_EQ(at_max.value, 4);
  // Inside, no pull: 2 um = 3.2 -> 3.
  EXPECT_EQ(target_to_usteps(2, -1000, 1000, m).value, 3);
}

// At the edge of the representable range: 201 um pitch, 200 usteps/rev; a limit of
// 1005000001 um is 1000000000.995 usteps, inward kPosMax, while the target on that limit rounds
// to kPosMax + 1. As documented, the target is pulled back onto the limit (not refused).
TEST(AxisEdges, TargetAtTheRepresentableLimitIsPulledOntoIt) {
  const Mechanics m{201, 200, 1};
  const int32_t max_um = 1'005'000'001;
  const UstepLimits lim = limits_to_usteps(0, max_um, m);
  ASSERT_EQ(lim.error, Error::None);
  EXPECT_EQ(lim.max, kPosMax);
  EXPECT_EQ(um_to_usteps(max_um, m, Round::Nearest).error, Error::OutOfLimits);
  const Converted t = target_to_usteps(max_um, 0, max_um, m);
  EXPECT_EQ(t.error, Error::None);
  EXPECT_EQ(t.value, kPosMax);
  // Mirror image at the lower end.
  const UstepLimits nlim = limits_to_usteps(-max_um, 0, m);
  ASSERT_EQ(nlim.error, Error::None);
  EXPECT_EQ(nlim.min, -kPosMax);
  const Converted nt = target_to_usteps(-max_um, -max_um, 0, m);
  EXPECT_EQ(nt.error, Error::None);
  EXPECT_EQ(nt.value, -kPosMax);
}

TEST(AxisEdges, EncoderInputBounds) {
  EXPECT_EQ(encoder_to_usteps({1, 0, 1}, 0).error, Error::BadCommand);
  EXPECT_EQ(encoder_to_usteps({1, 0, 1}, 256'001).error, Error::BadCommand);
  const StartPosition top = encoder_to_usteps({1, 0, 1}, 256'000);
  EXPECT_EQ(top.error, Error::None);
  EXPECT_EQ(top.pos, 256'000);
  EXPECT_EQ(top.homed, 1);
  // Far below the encoder zero: beyond -kPosMax is a typed error, not a wrapped position.
  const StartPosition low = encoder_to_usteps({-65535, 0, 1}, 51200);
  EXPECT_EQ(low.error, Error::OutOfLimits);
  EXPECT_EQ(low.homed, 0);
}

TEST(AxisEdges, StartPositionFallsBackAndRefusesBadCounters) {
  // A valid-flagged encoder whose reading cannot be converted: the saved counter is used.
  const EncoderReading broken{0, 16384, 1};
  const StartPosition s = start_position(&broken, {1234, 1}, 3200);
  EXPECT_EQ(s.error, Error::None);
  EXPECT_EQ(s.pos, 1234);
  // ... and with no usable counter either: unhomed.
  EXPECT_EQ(start_position(&broken, {1234, 0}, 3200).error, Error::NotHomed);
  // A saved counter outside the position range is not trusted, at either end.
  for (const int32_t bad : {kPosMax + 1, -kPosMax - 1}) {
    const StartPosition n = start_position(nullptr, {bad, 1}, 3200);
    EXPECT_EQ(n.error, Error::NotHomed) << bad;
    EXPECT_EQ(n.homed, 0);
    EXPECT_EQ(initial_state(n).homed, 0);
  }
  for (const int32_t edge : {kPosMax, -kPosMax}) {
    EXPECT_EQ(start_position(nullptr, {edge, 1}, 3200).pos, edge);
  }
}

TEST(AxisEdges, StepTimerRange) {
  EXPECT_FALSE(step_timer(0).has_value());
  EXPECT_TRUE(step_timer(kStepFreqMax).has_value());
  EXPECT_FALSE(step_timer(kStepFreqMax + 1).has_value());
  EXPECT_FALSE(step_timer(UINT32_MAX).has_value());
}

// state_valid is what step() relies on to force a Stop on a corrupted state: each invariant
// alone must make it false.
TEST(AxisEdges, StateInvariantsEachCount) {
  const State good{};
  ASSERT_TRUE(state_valid(good));
  State s = good;
  s.dir = 0;
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.dir = -1;
  EXPECT_TRUE(state_valid(s));
  s = good;
  s.jog_dir = 0;
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.jog_dir = -1;
  EXPECT_TRUE(state_valid(s));
  s = good;
  s.mode = static_cast<Mode>(4);
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.phase = static_cast<Phase>(4);
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.level = 2;
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.latch_min = 2;
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.latch_max = 2;
  EXPECT_FALSE(state_valid(s));
  s = good;
  s.homed = 2;
  EXPECT_FALSE(state_valid(s));
}

// The braking distance is 0 at or below the start speed, and outside its documented range
// (accel >= 1) it answers 0 instead of dividing by zero.
TEST(AxisEdges, StopDistanceOutsideItsRange) {
  EXPECT_EQ(stop_distance_fine(5000, 5000, 100), 0);
  EXPECT_EQ(stop_distance_fine(4000, 5000, 100), 0);
  EXPECT_GT(stop_distance_fine(5101, 5000, 100), 0);
  EXPECT_EQ(stop_distance_fine(1'000'000, 5000, 0), 0);
  EXPECT_EQ(stop_distance_fine(1'000'000, 5000, -7), 0);
}

// Names of enum bytes outside the enums (a corrupted state in a trace): a placeholder, never
// an out-of-bounds read; and no guard holds for an unknown edge.
TEST(AxisEdges, UnknownEnumBytesHavePlaceholderNames) {
  EXPECT_EQ(edge_letter(Edge::X), 'X');
  EXPECT_EQ(edge_letter(static_cast<Edge>(kEdgeCount)), '?');
  EXPECT_EQ(std::string(phase_name(Phase::Decel)), "DECEL");
  EXPECT_EQ(std::string(phase_name(static_cast<Phase>(9))), "?");
  EXPECT_EQ(std::string(mode_name(Mode::Home)), "home");
  EXPECT_EQ(std::string(mode_name(static_cast<Mode>(9))), "?");
  for (int p = 0; p < kPhaseCount; ++p) {
    EXPECT_FALSE(edge_guard(static_cast<Edge>(kEdgeCount), static_cast<Phase>(p), Class::Faster));
  }
}
