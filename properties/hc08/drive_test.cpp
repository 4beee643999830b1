// Excitation tables and the sequencer (core/hc08/drive) against seed 002 §1.7 and docs/hc08.md
// "Excitation". Adjacency is judged on the four coils in rotational order, worked out here.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "core/hc08/drive/drive.hpp"

namespace {

namespace d = ap::hc08_drive;

int coils_on(std::uint8_t p) { return std::popcount(static_cast<unsigned>(p & 0x0F)); }
// Two coils adjacent in rotational order (0-1, 1-2, 2-3, 3-0).
bool adjacent_pair(std::uint8_t p) { return p == 0b0011 || p == 0b0110 || p == 0b1100 || p == 0b1001; }
// The rotor's rest position of a pattern in half steps (0..7): coil k alone at 2k, coils k and
// k+1 at 2k + 1.
int rest(std::uint8_t p) {
  for (int k = 0; k < 4; ++k) {
    if (p == (1 << k)) return 2 * k;
    if (p == ((1 << k) | (1 << ((k + 1) % 4)))) return 2 * k + 1;
  }
  return -1;
}

const auto gen_drive = [] { return rc::gen::element(d::Drive::Full, d::Drive::Half); };
const auto gen_full = [] { return rc::gen::element(d::FullStep::TwoPhase, d::FullStep::Wave); };

TEST(Hc08Drive, TheReconstructedBytesForTheDefaultOrder) {
  // Phase 1..4 on PTA3..PTA6 [T Tab. 4.1]; the bytes are seed-002.md §1.7's reconstruction
  // (docs/hc08.md "Excitation": the thesis's codes were on its CD): two-phase 0x18 0x30 0x60
  // 0x48; half step 0x08 0x18 0x10 0x30 0x20 0x60 0x40 0x48.
  const std::array<std::uint8_t, 4> two{0x18, 0x30, 0x60, 0x48};
  const std::array<std::uint8_t, 8> half{0x08, 0x18, 0x10, 0x30, 0x20, 0x60, 0x40, 0x48};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(d::port_byte(d::kTwoPhase.pattern[i], {}), two[i]) << i;
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(d::port_byte(d::kHalf.pattern[i], {}), half[i]) << i;
  EXPECT_EQ(d::steps_per_rev(d::Drive::Full), 40);
  EXPECT_EQ(d::steps_per_rev(d::Drive::Half), 80);
}

RC_GTEST_PROP(Hc08DriveProps, EveryHalfStepChangesExactlyOneCoil, ()) {
  d::Sequencer s(d::Drive::Half, *gen_full());
  const auto moves = *rc::gen::container<std::vector<bool>>(rc::gen::arbitrary<bool>());
  for (const bool fwd : moves) {
    const std::uint8_t before = s.pattern();
    s.step(fwd ? 1 : -1);
    RC_ASSERT(coils_on(static_cast<std::uint8_t>(before ^ s.pattern())) == 1);
    RC_ASSERT(coils_on(s.pattern()) == 1 || adjacent_pair(s.pattern()));  // never two opposite coils
  }
}

RC_GTEST_PROP(Hc08DriveProps, FullStepEnergisesTwoAdjacentCoilsOrOne, ()) {
  const auto f = *gen_full();
  d::Sequencer s(d::Drive::Full, f);
  const auto moves = *rc::gen::container<std::vector<bool>>(rc::gen::arbitrary<bool>());
  for (const bool fwd : moves) {
    s.step(fwd ? 1 : -1);
    if (f == d::FullStep::TwoPhase) {
      RC_ASSERT(adjacent_pair(s.pattern()));
    } else {
      RC_ASSERT(coils_on(s.pattern()) == 1);
    }
  }
}

RC_GTEST_PROP(Hc08DriveProps, SuccessivePatternsAreAdjacentRestPositions, ()) {
  const auto drive = *gen_drive();
  d::Sequencer s(drive, *gen_full());
  const int step = drive == d::Drive::Half ? 1 : 2;  // half steps per step
  const auto moves = *rc::gen::container<std::vector<bool>>(rc::gen::arbitrary<bool>());
  for (const bool fwd : moves) {
    const int a = rest(s.pattern());
    s.step(fwd ? 1 : -1);
    const int b = rest(s.pattern());
    RC_ASSERT(a >= 0 && b >= 0);
    RC_ASSERT(((b - a + 8) % 8) == (fwd ? step : 8 - step));
  }
}

RC_GTEST_PROP(Hc08DriveProps, ReversalIsTheExactInverseAndNBackReturns, ()) {
  d::Sequencer s(*gen_drive(), *gen_full());
  const auto pre = *rc::gen::inRange(0, 20);
  for (int i = 0; i < pre; ++i) s.step(1);
  const auto n = *rc::gen::inRange(0, 200);
  const std::uint8_t start = s.pattern();
  std::vector<std::uint8_t> out;
  for (int i = 0; i < n; ++i) {
    out.push_back(s.pattern());
    s.step(1);
  }
  for (int i = n - 1; i >= 0; --i) {
    s.step(-1);
    RC_ASSERT(s.pattern() == out[static_cast<std::size_t>(i)]);  // backwards, byte for byte
  }
  RC_ASSERT(s.pattern() == start);
}

RC_GTEST_PROP(Hc08DriveProps, AnyPhaseOrderDrivesOnlyTheMotorPinsOneToOne, ()) {
  d::PhaseOrder o;
  o.phase = {0, 1, 2, 3};
  const auto perm = *rc::gen::inRange(0, 24);
  std::next_permutation(o.phase.begin(), o.phase.end());  // at least one other order
  for (int i = 0; i < perm; ++i) std::next_permutation(o.phase.begin(), o.phase.end());
  RC_ASSERT(d::is_permutation(o));
  for (std::uint8_t p = 0; p < 16; ++p) {
    const std::uint8_t b = d::port_byte(p, o);
    RC_ASSERT((b & ~0x78U) == 0U);  // PTA3..6 only
    RC_ASSERT(coils_on(p) == std::popcount(static_cast<unsigned>(b)));
  }
}

TEST(Hc08Drive, ChangingTheDriveKeepsTheCoilsOrMovesHalfAStepForward) {
  d::Sequencer s(d::Drive::Half, d::FullStep::TwoPhase);
  s.step(1);  // 0b0011: two coils, a two-phase full-step pattern
  EXPECT_EQ(s.set_drive(d::Drive::Full), 0);
  EXPECT_EQ(s.pattern(), 0b0011);
  EXPECT_EQ(s.set_drive(d::Drive::Half), 0);
  s.step(1);  // 0b0010: one coil, not in the two-phase table
  EXPECT_EQ(s.set_drive(d::Drive::Full), 1);
  EXPECT_EQ(s.pattern(), 0b0110);  // the next forward half step
}

}  // namespace
