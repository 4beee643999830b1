// The XY board's parts behind the core's buses, as device models (docs/sim.md "The simulated
// board", docs/device-models.md): the two TMC2130 drivers and the MB85RS256B FRAM on SPI, the
// TMP117 and the ICM-20789 on one I2C bus. One definition of them, of how a motor output turns
// a motor through its driver and of what a power cycle keeps, for every fixture that runs the
// board core (core/xy/board) on them: the simulated board (sim/xy/board.hpp) and the rig of the
// board tests and the board fuzz target (sim/xy/rig/board_rig.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/xy/axis/axis.hpp"
#include "core/xy/board/board.hpp"
#include "models/xy/fram/mb85rs256b.hpp"
#include "models/xy/i2c/bus.hpp"
#include "models/xy/icm20789/device.hpp"
#include "models/xy/tmc2130/device.hpp"
#include "models/xy/tmp117/device.hpp"

namespace ap::sim::xy {

// A part on the sensor bus that can be taken off it: absent, it acknowledges nothing
// (AddressNack), as an unpowered chip or a broken trace does.
template <class D>
struct Plug : model::xy_i2c::Device {
  D chip{};
  bool present = true;
  xy_i2c::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx,
                              std::span<std::uint8_t> rx) override {
    return present ? chip.transfer(address, tx, rx) : xy_i2c::Status::AddressNack;
  }
};

struct BoardParts {
  model::Mb85rs256b fram;
  std::array<model::xy_tmc2130::Device, xy_board::kAxes> tmc{};
  Plug<model::xy_tmp117::Device> tmp117{};
  Plug<model::xy_icm20789::Device> gyro{};
  model::xy_i2c::Bus i2c{};
  // Every transaction on the bus fails like this (a stuck bus), until healed; nullopt: none.
  std::optional<xy_i2c::Status> bus_fault;

  BoardParts() {
    i2c.attach(tmp117);
    i2c.attach(gyro);
  }
  // The bus holds this object's own sensors: a copy's bus would still reach the original's.
  BoardParts(const BoardParts&) = delete;
  BoardParts& operator=(const BoardParts&) = delete;

  // The core's SPI and I2C ports straight to the models.
  void wire(xy_board::Hardware& hw) {
    hw.tmc = {tmc[0].port(), tmc[1].port()};
    hw.fram = fram.bus();
    hw.i2c = i2c.port();
  }

  // One tick's STEP edges of axis `a` through its driver, in 1/256 full steps turned: the
  // driver decides whether the edges turn the motor (DRV_ENN from the core's enable,
  // CHOPCONF.TOFF) and how far (CHOPCONF.MRES), docs/device-models.md.
  std::int64_t turn(std::size_t a, bool enable, std::int64_t edges, int dir) {
    tmc[a].set_drv_enn(!enable);
    return tmc[a].step(edges, dir);
  }

  // One board tick on the drivers' clock (their standstill detection and current reduction
  // count it).
  void drivers_tick() {
    for (auto& d : tmc) d.elapse_us(xy_axis::kTickUs);
  }
  // The models' transfer logs are test hooks; a long run would only grow them.
  void clear_logs() {
    for (auto& d : tmc) d.clear_log();
    i2c.clear_log();
  }

  // Power cycle: the drivers and the sensors lose their registers, the FRAM keeps its contents.
  void power_cycle() {
    for (auto& d : tmc) d.power_cycle();
    tmp117.chip.power_on_reset();
    gyro.chip.power_on_reset();
  }

  // A stuck bus (every transaction fails with `s`) or a healed one.
  void fail_bus(xy_i2c::Status s) {
    bus_fault = s;
    i2c.fail_at(0, s, true);
  }
  void heal_bus() {
    bus_fault.reset();
    i2c.heal();
  }
  // How every transaction to each sensor ends now.
  xy_i2c::Status tmp117_answers() const {
    return bus_fault ? *bus_fault : (tmp117.present ? xy_i2c::Status::Ok : xy_i2c::Status::AddressNack);
  }
  xy_i2c::Status gyro_answers() const {
    return bus_fault ? *bus_fault : (gyro.present ? xy_i2c::Status::Ok : xy_i2c::Status::AddressNack);
  }
};

}  // namespace ap::sim::xy
