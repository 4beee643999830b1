// Not firmware: a probe for ci/m4-build's RAM figure of the hc08 profile. All the unit's state
// lives in one ap::hc08_board::Board object; the symbol's size (nm -S) is sizeof(Board) as the
// cross compiler lays it out.
#include "core/hc08/board/board.hpp"

extern "C" {
extern const unsigned char ap_hc08_state_bytes[sizeof(ap::hc08_board::Board)];
const unsigned char ap_hc08_state_bytes[sizeof(ap::hc08_board::Board)] = {};
}
