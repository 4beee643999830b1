// The XY board's main loop (docs/qemu.md "Images"): one Board object in static storage, booted
// once, then one core tick per 1 ms control tick. The link's bytes move from the interrupt's
// ring into the core in thread mode, so the core is never entered from two contexts.
#include <cstddef>
#include <cstdint>

#include "core/xy/board/board.hpp"
#include "firmware/xy/app.hpp"
#include "firmware/xy/board_port.hpp"
#include "firmware/xy/periph.hpp"
#include "firmware/xy/stack.hpp"
#include "protocol/xy/cosim/wire.hpp"

namespace {
// Constructed before run() by the reset handler's constructor pass; it touches no hardware
// until boot().
ap::xy_board::Board the_board{ap::xy_fw::board_hardware()};
}  // namespace

namespace ap::xy_fw {

void run() {
  periph_init();
  port_init();
  xy_board::Board* b = &the_board;
  (void)b->boot();
  std::uint32_t ticks = 0;
  while (tick_wait()) {
    std::uint8_t buf[64];
    for (std::size_t n = link_take(buf, sizeof buf); n > 0; n = link_take(buf, sizeof buf)) {
      b->uart_rx(std::span<const std::uint8_t>(buf, n));
    }
    b->tick();
    ++ticks;
    if (stack_overflowed()) fault(xy_cosim::stop::kStackPaint, 0, 0, 0, 0);
    if (handler_stack_overflowed()) fault(xy_cosim::stop::kHandlerStackPaint, 0, 0, 0, 0);
    tick_done(ticks, take_tx_count(), b->axis_state(xy_board::Axis::X).pos, b->axis_state(xy_board::Axis::Y).pos);
  }
  report(stack_used(), stack_size(), ticks);
}

}  // namespace ap::xy_fw
