// Compiles every header-only part of ap_xy_axis under the core flags and pins the G17 and
// eq. 7-2 vectors of seed-000.md section 9 at compile time.
#include "core/xy/axis/position.hpp"
#include "core/xy/axis/step_timer.hpp"
#include "core/xy/axis/units.hpp"
#include "core/xy/axis/watchdog.hpp"

namespace ap::xy_axis {
namespace {
constexpr bool timer_is(uint32_t f, uint16_t psc, uint16_t arr) {
  const auto t = step_timer(f);
  return t.has_value() && t->psc == psc && t->arr == arr;
}
static_assert(timer_is(1000, 1, 39999));
static_assert(timer_is(1221, 0, 65519));
static_assert(timer_is(1, 1220, 65519));
static_assert(timer_is(51200, 0, 1561));
static_assert(!step_timer(0).has_value());
static_assert(encoder_to_usteps({3, 8192, 1}, 16 * 200).pos == 11200);
static_assert(encoder_to_usteps({0, 16383, 1}, 256 * 200).pos == 51196);
}  // namespace
}  // namespace ap::xy_axis
