// Not firmware: a probe for ci/m4-build's RAM figure. The core keeps no static state; all of it
// lives in one ap::xy_board::Board object, which the images place in static storage (src/main.cpp). The symbol's
// size (nm -S) is sizeof(Board) as the cross compiler lays it out.
#include "core/xy/board/board.hpp"

extern "C" {
extern const unsigned char ap_xy_state_bytes[sizeof(ap::xy_board::Board)];
const unsigned char ap_xy_state_bytes[sizeof(ap::xy_board::Board)] = {};
}
