// The edges of isqrt's range, checked where it is compiled for the core.
#include "core/intmath/isqrt.hpp"

namespace ap::intmath {
static_assert(isqrt(0) == 0 && isqrt(1) == 1 && isqrt(3) == 1 && isqrt(4) == 2);
static_assert(isqrt(0xFFFFFFFFFFFFFFFFULL) == 0xFFFFFFFFULL);
static_assert(isqrt(0xFFFFFFFE00000001ULL) == 0xFFFFFFFFULL && isqrt(0xFFFFFFFE00000000ULL) == 0xFFFFFFFEULL);
}  // namespace ap::intmath
