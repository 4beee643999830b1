// Counting is constexpr in its header (counting.hpp) so the firmware, the tests and the proofs
// read one definition; this unit gives the library an object and pins the thesis's examples.
#include "core/unit3/axis/counting.hpp"

namespace ap::unit3_axis {

// Seed 001 §2.3: Y000000000016000; in full step is 500 pulses, Y000000000000500; at 1/32 is 500.
static_assert(plan_move(0, 1, 16000, 0).pulses == 500 && plan_move(0, 1, 16000, 0).target == 16000);
static_assert(plan_move(0, 1, 500, 5).pulses == 500 && plan_move(0, 1, 500, 5).target == 500);
// Eq. 5: M2 (0.4 mm) 16000 counts = 2.5 rev = 1 mm; M6 (1 mm) 6400 counts = 1 mm.
static_assert(position_um(16000, 0) == 1000 && position_um(6400, 4) == 1000);

}  // namespace ap::unit3_axis
