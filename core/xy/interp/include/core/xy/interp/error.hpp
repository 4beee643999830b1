// Typed refusals of the interpolators (docs/interpolation.md "Errors"). A refused input builds
// nothing: make() returns a zero-length interpolator together with the error.
#pragma once

#include <cstdint>

namespace ap::xy_interp {

enum class Error : uint8_t {
  None = 0,
  DeltaOutOfRange,  // Line: some |delta_i| > Line::kMaxDelta
  CoordOutOfRange,  // Arc: some |offset| > Arc::kMaxCoord; Segment: |absolute| > Segment::kMaxAbs
  ZeroRadius,       // Arc: start == centre
  EndAtCentre,      // Arc: end == centre (the end has no angle)
  ArcChangesZ,      // Segment::arc: from.z != to.z (helices are not supported)
};

}  // namespace ap::xy_interp
