// The ramp table and step timer (core/unit3/ramp) against docs/unit3.md "Ramp and step timer":
// 16 MHz [T], prescaler 64, entry i = 25 + 10 i + i (i - 1) / 2 Hz (25 .. 800 Hz, the step
// between entries 10, 11, ..., 40 Hz), one entry per 10 ms. The expected values are worked out
// here from those numbers, not read from the core's constants.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <cstdlib>

#include "core/unit3/ramp/ramp.hpp"

namespace {

namespace r = ap::unit3_ramp;

TEST(Unit3Ramp, TableByHand) {
  // TOP = round(250 000 / f) - 1.
  EXPECT_EQ(r::kTable.top[0], 9999);   // 25 Hz
  EXPECT_EQ(r::kTable.top[1], 7142);   // 35 Hz: 7142.86 clocks, rounded to 7143
  EXPECT_EQ(r::kTable.top[2], 5434);   // 46 Hz: 5434.78 -> 5435
  EXPECT_EQ(r::kTable.top[6], 2499);   // 25 + 60 + 15 = 100 Hz
  EXPECT_EQ(r::kTable.top[15], 892);   // 25 + 150 + 105 = 280 Hz: 892.86 -> 893
  EXPECT_EQ(r::kTable.top[30], 328);   // 25 + 300 + 435 = 760 Hz: 328.95 -> 329
  EXPECT_EQ(r::kTable.top[31], 312);   // 800 Hz: 250000/800 = 312.5, rounded up to 313 clocks
}

// The documented frequency of entry i (docs/unit3.md), in Hz.
double doc_hz(int i) { return 25.0 + 10.0 * i + i * (i - 1) / 2.0; }
double table_hz(int i) { return 250000.0 / (r::kTable.top[static_cast<std::size_t>(i)] + 1); }

TEST(Unit3Ramp, EveryEntryWithinItsRoundingAndFalling) {
  for (int i = 0; i < 32; ++i) {
    // Rounding TOP to the nearest clock: at most half a clock of the period.
    EXPECT_LE(std::abs(250000.0 / table_hz(i) - 250000.0 / doc_hz(i)), 0.5) << "entry " << i;
    if (i > 0) {
      EXPECT_LT(r::kTable.top[static_cast<std::size_t>(i)], r::kTable.top[static_cast<std::size_t>(i - 1)]);
    }
  }
}

// The thesis (001_*.txt:1061-1063): "at low speeds the motors accelerate much more slowly than at
// higher speeds". One entry per 10 ms, so an entry's frequency step is the acceleration there:
// docs/unit3.md decides 10 Hz from entry 0 to 1 (1 000 pulses/s^2), 40 Hz from 30 to 31
// (4 000 pulses/s^2), each step 1 Hz above the one before (the "linear" of 001_*.txt:1067).
// Measured on the table's own TOPs, each frequency within half a clock of its period.
TEST(Unit3Ramp, TheLowEndAcceleratesMoreSlowlyThanTheHighEnd) {
  const auto step = [](int i) { return table_hz(i) - table_hz(i - 1); };
  EXPECT_NEAR(step(1), 10.0, 0.1);   // 35 - 25 Hz; TOPs 9999 and 7142
  EXPECT_NEAR(step(31), 40.0, 2.0);  // 800 - 760 Hz; a clock at 800 Hz is 2.6 Hz
  double low = 0.0, high = 0.0;
  for (int i = 1; i <= 8; ++i) low += step(i);     // 10 + ... + 17 = 108 Hz
  for (int i = 24; i <= 31; ++i) high += step(i);  // 33 + ... + 40 = 292 Hz
  EXPECT_NEAR(low, 108.0, 1.5);
  EXPECT_NEAR(high, 292.0, 1.5);
  EXPECT_LT(2.5 * low, high);
}

TEST(Unit3Ramp, TimerPeriodIsTopPlusOne) {
  r::Timer t;
  t.start(9);  // 10 clocks per match
  std::uint32_t at = 0;
  EXPECT_EQ(t.advance(9, at), 0U);
  EXPECT_EQ(t.advance(1, at), 1U);
  EXPECT_EQ(at, 1U);
  EXPECT_EQ(t.advance(25, at), 2U);  // clocks 10 and 20 of these 25
  EXPECT_EQ(at, 10U);
  EXPECT_EQ(t.count(), 5);
}

TEST(Unit3Ramp, LoweringTopBelowTheCountFiresAtOnce) {
  // TCNT at 400 when TOP drops to 312: without the guard the compare would come only after
  // TCNT wrapped through 65536 (65 448 clocks, 262 ms); with it, on the next clock.
  r::Timer t;
  t.start(9999);
  std::uint32_t at = 0;
  ASSERT_EQ(t.advance(400, at), 0U);
  t.set_top(312);
  EXPECT_EQ(t.advance(1, at), 1U);
  EXPECT_EQ(t.advance(312, at), 0U);
  EXPECT_EQ(t.advance(1, at), 1U);
}

// A PC move of n pulses run by the ramp rule and the timer alone: returns the entry of the
// last pulse and checks the entry moves by at most one per interval.
struct MoveRun {
  int last_entry = -1;
  std::uint64_t pulses = 0;
  int max_entry = 0;
  bool steps_ok = true;
};
MoveRun run_move(std::uint64_t n) {
  MoveRun m;
  r::Timer t;
  std::uint8_t entry = 0;
  t.start(r::kTable.top[0]);
  std::uint64_t remaining = n;
  for (std::uint64_t tick = 0; remaining > 0 && tick < 10'000'000; ++tick) {
    if (tick > 0 && tick % 10 == 0) {
      const auto nx = r::next_entry(entry, 31, false, remaining);
      if (nx.stop || (nx.entry > entry + 1) || (nx.entry + 1 < entry)) m.steps_ok = false;
      entry = nx.entry;
      t.set_top(r::kTable.top[entry]);
    }
    std::uint32_t at = 0;
    const auto p = t.advance(250, at);
    if (p > 1) m.steps_ok = false;
    if (p == 1) {
      ++m.pulses;
      --remaining;
      m.last_entry = entry;
    }
    if (entry > m.max_entry) m.max_entry = entry;
  }
  return m;
}

TEST(Unit3Ramp, EveryMoveUpTo3000PulsesEndsAtTheStartSpeed) {
  // 3000 pulses reach the top entry (a move that climbs to entry 31 and back down sends about
  // 200: 10 ms at each entry from 25 Hz to 800 Hz, twice).
  bool reached_top = false;
  for (std::uint64_t n = 1; n <= 3000; ++n) {
    const MoveRun m = run_move(n);
    ASSERT_EQ(m.pulses, n);
    ASSERT_TRUE(m.steps_ok) << n;
    ASSERT_EQ(m.last_entry, 0) << "a move of " << n << " pulses ended above the start speed";
    reached_top = reached_top || m.max_entry == 31;
  }
  EXPECT_TRUE(reached_top);
}

TEST(Unit3Ramp, TheStickStopsAndReversesOnlyFromEntryZero) {
  for (std::uint8_t e = 0; e < 32; ++e) {
    const auto n = r::next_entry(e, 31, true, r::kNoEnd);
    EXPECT_EQ(n.stop, e == 0);
    if (e > 0) {
      EXPECT_EQ(n.entry, e - 1);
    }
  }
}

RC_GTEST_PROP(Unit3RampProps, EntryMovesByAtMostOneTowardsTheTarget, ()) {
  const auto e = *rc::gen::inRange<std::uint8_t>(0, 32);
  const auto target = *rc::gen::inRange<std::uint8_t>(0, 32);
  const auto n = r::next_entry(e, target, false, r::kNoEnd);
  RC_ASSERT(!n.stop);
  const int want = target > e ? e + 1 : target < e ? e - 1 : e;
  RC_ASSERT(static_cast<int>(n.entry) == want);
}

}  // namespace
