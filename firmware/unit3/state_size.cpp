// Not firmware: a probe for ci/m4-build's RAM figure of the unit3 profile. All the unit's state
// lives in one ap::unit3_board::Unit object; the symbol's size (nm -S) is sizeof(Unit) as the
// cross compiler lays it out.
#include "core/unit3/board/unit.hpp"

extern "C" {
extern const unsigned char ap_unit3_state_bytes[sizeof(ap::unit3_board::Unit)];
const unsigned char ap_unit3_state_bytes[sizeof(ap::unit3_board::Unit)] = {};
}
