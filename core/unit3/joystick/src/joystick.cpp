// The joystick mapping is constexpr and lives in its header (joystick.hpp), so the firmware,
// the tests and the proof obligations read the same definition; this unit gives the library
// an object file and checks the thesis's anchor points at compile time.
#include "core/unit3/joystick/joystick.hpp"

namespace ap::unit3_joystick {

static_assert(deflection(512) == Deflection{});       // neutral [T: 512 +- 12]
static_assert(deflection(500) == Deflection{});       // dead-band ends stop [D]
static_assert(deflection(524) == Deflection{});
static_assert(deflection(497).index == 0 && deflection(497).dir == -1);  // eq. 6: (512-497)/16 = 0
static_assert(deflection(1023).index == 31);          // eq. 7: (1023-524)/16 = 31

}  // namespace ap::unit3_joystick
