// The board's I2C sensors as the echo reference model sees them (models/xy/echo sensors_of,
// docs/echo-model.md): the device models' registers and how the bus answers each part, never
// the board core's values. The simulated board and the rig's users give the model the same view.
#pragma once

#include "models/xy/echo/board_checker.hpp"
#include "sim/xy/rig/board_rig.hpp"
#include "sim/xy/rig/parts.hpp"

namespace ap::sim::xy {

inline model::xy_echo::Sensors sensors_of(const BoardParts& p) {
  return model::xy_echo::sensors_of(p.tmp117.chip, p.tmp117_answers(), p.gyro.chip, p.gyro_answers());
}

// Boot facts of the rig's board, the sensors as they stood when it configured them.
inline model::xy_echo::Boot boot_facts_of(const Rig& r) {
  model::xy_echo::Boot b = model::xy_echo::boot_facts(*r.board, r.in);
  b.sensors = sensors_of(r);
  return b;
}

}  // namespace ap::sim::xy
