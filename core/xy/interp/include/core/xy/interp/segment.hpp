// One interpolated path segment, a line or an arc, built from absolute integer step
// coordinates (docs/interpolation.md "Segment"). A tagged union: std::variant may throw, and
// core/ has no exceptions. Line and Arc are trivially copyable, so a Segment is too: a caller
// can count a segment's moves by iterating a copy.
//
// Ranges: absolute coordinates (from, to, centre) within +-kMaxAbs = 2^23 (419 m at 20 steps/mm),
// so a line's delta is within Line::kMaxDelta = 2^24; an arc's offsets from its centre must
// also be within Arc::kMaxCoord = 2^20 (else CoordOutOfRange).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/xy/interp/arc.hpp"
#include "core/xy/interp/error.hpp"
#include "core/xy/interp/line.hpp"

namespace ap::xy_interp {

struct SegmentResult;

struct Segment {
 public:
  enum class Kind : uint8_t { Line, Arc };
  static constexpr int32_t kMaxAbs = int32_t{1} << 23;

  // A straight move in X, Y and Z.
  [[nodiscard]] static constexpr SegmentResult line(std::array<int32_t, 3> from, std::array<int32_t, 3> to);
  // An arc in the XY plane about `centre`; from.z must equal to.z (no helices: ArcChangesZ).
  // to == from is a full circle (arc.hpp).
  [[nodiscard]] static constexpr SegmentResult arc(std::array<int32_t, 3> from, std::array<int32_t, 3> to,
                                                   std::array<int32_t, 2> centre, Turn turn);

  // A zero-length line at the origin (what a refused make gives).
  constexpr Segment() : line_() {}

  [[nodiscard]] constexpr Kind kind() const { return kind_; }
  [[nodiscard]] constexpr bool done() const { return kind_ == Kind::Line ? line_.done() : arc_.done(); }
  // Line: moves() exactly; arc: the termination bound Arc::max_moves().
  [[nodiscard]] constexpr uint32_t max_moves() const { return kind_ == Kind::Line ? line_.moves() : arc_.max_moves(); }

  // The per-axis move {dx, dy, dz}, each in {-1, 0, 1}; zeros once done().
  constexpr std::array<int8_t, 3> next() {
    if (kind_ == Kind::Line) {
      return line_.next();
    }
    const std::array<int8_t, 2> m = arc_.next();
    return {m[0], m[1], 0};
  }

  // Absolute.
  [[nodiscard]] constexpr std::array<int32_t, 3> position() const {
    if (kind_ == Kind::Line) {
      const std::array<int32_t, 3> p = line_.position();
      return {origin_[0] + p[0], origin_[1] + p[1], origin_[2] + p[2]};
    }
    const std::array<int32_t, 2> p = arc_.position();
    return {origin_[0] + p[0], origin_[1] + p[1], origin_[2]};
  }

 private:
  static constexpr bool in_range(int32_t v) { return v >= -kMaxAbs && v <= kMaxAbs; }

  constexpr Segment(const Line& l, std::array<int32_t, 3> origin) : kind_(Kind::Line), origin_(origin), line_(l) {}
  constexpr Segment(const Arc& a, std::array<int32_t, 3> origin) : kind_(Kind::Arc), origin_(origin), arc_(a) {}

  Kind kind_ = Kind::Line;
  std::array<int32_t, 3> origin_{};  // line: its start; arc: {centre x, centre y, z}
  union {
    Line line_;
    Arc arc_;
  };
};

struct SegmentResult {
  Segment segment;
  Error error;
};

constexpr SegmentResult Segment::line(std::array<int32_t, 3> from, std::array<int32_t, 3> to) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (!in_range(from[k]) || !in_range(to[k])) {
      return {Segment{}, Error::CoordOutOfRange};
    }
  }
  // |to - from| <= 2^24 = Line::kMaxDelta: never refused.
  const LineResult r = Line::make({to[0] - from[0], to[1] - from[1], to[2] - from[2]});
  if (r.error != Error::None) {
    return {Segment{}, r.error};
  }
  return {Segment{r.line, from}, Error::None};
}

constexpr SegmentResult Segment::arc(std::array<int32_t, 3> from, std::array<int32_t, 3> to,
                                     std::array<int32_t, 2> centre, Turn turn) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (!in_range(from[k]) || !in_range(to[k])) {
      return {Segment{}, Error::CoordOutOfRange};
    }
  }
  if (!in_range(centre[0]) || !in_range(centre[1])) {
    return {Segment{}, Error::CoordOutOfRange};
  }
  if (from[2] != to[2]) {
    return {Segment{}, Error::ArcChangesZ};
  }
  // Differences of values within +-2^23 fit int32; Arc::make range-checks them.
  const ArcResult r = Arc::make({from[0] - centre[0], from[1] - centre[1]}, {to[0] - centre[0], to[1] - centre[1]}, turn);
  if (r.error != Error::None) {
    return {Segment{}, r.error};
  }
  return {Segment{r.arc, {centre[0], centre[1], from[2]}}, Error::None};
}

}  // namespace ap::xy_interp
