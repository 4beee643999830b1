// The rig's I2C sensors as the echo reference model sees them (models/xy/echo sensors_of): the
// device models' registers and how the bus answers each part, never the board's values.
#pragma once

#include "board_rig.hpp"
#include "models/xy/echo/board_checker.hpp"

namespace ap::xy_board::test {

inline model::xy_echo::Sensors sensors_of(const Rig& r) {
  return model::xy_echo::sensors_of(r.tmp117.chip, r.tmp117_answers(), r.gyro.chip, r.gyro_answers());
}

// Boot facts of the rig's board, the sensors as they stood when it configured them.
inline model::xy_echo::Boot boot_facts_of(const Rig& r) {
  model::xy_echo::Boot b = model::xy_echo::boot_facts(*r.board, r.in);
  b.sensors = sensors_of(r);
  return b;
}

}  // namespace ap::xy_board::test
