// The rig's I2C sensors as the echo reference model sees them (models/echo sensors_of): the
// device models' registers and how the bus answers each part, never the board's values.
#pragma once

#include "board_rig.hpp"
#include "models/echo/board_checker.hpp"

namespace ap::board::test {

inline model::echo::Sensors sensors_of(const Rig& r) {
  return model::echo::sensors_of(r.tmp117.chip, r.tmp117_answers(), r.gyro.chip, r.gyro_answers());
}

// Boot facts of the rig's board, the sensors as they stood when it configured them.
inline model::echo::Boot boot_facts_of(const Rig& r) {
  model::echo::Boot b = model::echo::boot_facts(*r.board, r.in);
  b.sensors = sensors_of(r);
  return b;
}

}  // namespace ap::board::test
