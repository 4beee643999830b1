// Segment (core/xy/interp/segment.hpp): absolute coordinates in, the same moves as Line and Arc
// out (docs/interpolation.md "Segment"). Expected values typed from the thesis (seed-003.md).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "core/xy/interp/segment.hpp"

namespace {

using ap::xy_interp::Error;
using ap::xy_interp::Segment;
using ap::xy_interp::Turn;
using A3 = std::array<int32_t, 3>;

TEST(InterpSegment, LineFromAbsoluteCoordinates) {
  // The thesis's (0,0)->(7,3) (seed §3.2), shifted to start at (10,-5) with Z at 3.
  const auto r = Segment::line({10, -5, 3}, {17, -2, 3});
  ASSERT_EQ(r.error, Error::None);
  Segment s = r.segment;
  EXPECT_EQ(s.kind(), Segment::Kind::Line);
  EXPECT_EQ(s.max_moves(), 7U);
  const std::vector<A3> want{{10, -5, 3}, {11, -5, 3}, {12, -4, 3}, {13, -4, 3}, {14, -3, 3}, {15, -3, 3}, {16, -2, 3}, {17, -2, 3}};
  std::vector<A3> got{s.position()};
  while (!s.done()) {
    s.next();
    got.push_back(s.position());
  }
  EXPECT_EQ(got, want);
  EXPECT_EQ(s.next(), (std::array<int8_t, 3>{0, 0, 0}));
}

TEST(InterpSegment, ThesisN05FromAbsoluteCoordinates) {
  // seed §2.5: N05 from (300,300) mm to (300,100) mm about (300,200) mm, CW, at 20 steps/mm.
  const auto r = Segment::arc({6000, 6000, 0}, {6000, 2000, 0}, {6000, 4000}, Turn::Cw);
  ASSERT_EQ(r.error, Error::None);
  Segment s = r.segment;
  EXPECT_EQ(s.kind(), Segment::Kind::Arc);
  bool passed = false;
  int moves = 0;
  while (!s.done()) {
    const auto m = s.next();
    ASSERT_EQ(m[2], 0);
    ++moves;
    passed = passed || s.position() == A3{8000, 4000, 0};  // (400, 200) mm
    ASSERT_GE(s.position()[0], 6000);
  }
  EXPECT_TRUE(passed);
  EXPECT_EQ(s.position(), (A3{6000, 2000, 0}));
  EXPECT_EQ(moves, 2 * 2828);  // seed §3.3: 2828 moves per quadrant at r = 2000
}

TEST(InterpSegment, CountingACopyLeavesTheOriginal) {
  const auto r = Segment::arc({105, 7, -4}, {5, 107, -4}, {5, 7}, Turn::Ccw);  // a quarter, r = 100
  ASSERT_EQ(r.error, Error::None);
  Segment copy = r.segment;
  uint32_t counted = 0;
  while (!copy.done()) {
    copy.next();
    ++counted;
  }
  EXPECT_EQ(counted, 141U);  // seed §3.3: 141 moves per quadrant at r = 100
  Segment original = r.segment;
  EXPECT_EQ(original.position(), (A3{105, 7, -4}));
  EXPECT_FALSE(original.done());
  uint32_t again = 0;
  while (!original.done()) {
    original.next();
    ++again;
  }
  EXPECT_EQ(again, counted);
  EXPECT_LE(counted, r.segment.max_moves());
}

TEST(InterpSegment, BadInputIsRefused) {
  constexpr int32_t kAbs = 1 << 23;  // docs/interpolation.md: |absolute| <= 2^23
  EXPECT_EQ(Segment::line({0, 0, 0}, {kAbs + 1, 0, 0}).error, Error::CoordOutOfRange);
  EXPECT_EQ(Segment::line({0, -kAbs - 1, 0}, {0, 0, 0}).error, Error::CoordOutOfRange);
  EXPECT_EQ(Segment::line({-kAbs, 0, 0}, {kAbs, 0, 0}).error, Error::None);
  EXPECT_EQ(Segment::arc({10, 0, 0}, {10, 0, 1}, {0, 0}, Turn::Cw).error, Error::ArcChangesZ);
  EXPECT_EQ(Segment::arc({10, 0, 0}, {10, 0, 0}, {10, 0}, Turn::Cw).error, Error::ZeroRadius);
  EXPECT_EQ(Segment::arc({10, 0, 0}, {0, 0, 0}, {0, 0}, Turn::Cw).error, Error::EndAtCentre);
  EXPECT_EQ(Segment::arc({(1 << 20) + 1, 0, 0}, {0, 5, 0}, {0, 0}, Turn::Cw).error, Error::CoordOutOfRange);
  EXPECT_EQ(Segment::arc({0, 0, 0}, {0, 5, 0}, {kAbs + 1, 0}, Turn::Cw).error, Error::CoordOutOfRange);
  const auto refused = Segment::arc({10, 0, 0}, {10, 0, 1}, {0, 0}, Turn::Cw).segment;
  EXPECT_TRUE(refused.done());
  EXPECT_EQ(refused.position(), (A3{0, 0, 0}));
}

TEST(InterpSegment, ThreeAxisLine) {
  Segment s = Segment::line({0, 0, 0}, {-3, 6, 2}).segment;
  int moves = 0;
  while (!s.done()) {
    const auto m = s.next();
    ASSERT_EQ(m[1], 1);  // Y is the major axis
    ++moves;
  }
  EXPECT_EQ(moves, 6);
  EXPECT_EQ(s.position(), (A3{-3, 6, 2}));
}

}  // namespace
