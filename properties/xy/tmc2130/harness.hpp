#pragma once
// Test wiring: a driver talking to the device model through a recorder that keeps the raw
// MOSI bytes and can make the bus fail.
#include <vector>

#include "core/xy/tmc2130/driver.hpp"
#include "models/xy/tmc2130/device.hpp"

namespace tmc_test {

namespace chip = ap::xy_tmc2130;
using ap::model::xy_tmc2130::Device;

struct Bench {
  Device device;
  std::vector<chip::Datagram> mosi;
  bool bus_fails = false;
  chip::Driver driver{chip::SpiPort{&Bench::spi, this}};

  static bool spi(void* context, const chip::Datagram& tx, chip::Datagram& rx) {
    auto* self = static_cast<Bench*>(context);
    if (self->bus_fails) return false;
    self->mosi.push_back(tx);
    rx = self->device.transfer(tx);
    return true;
  }
  void clear() {
    mosi.clear();
    device.clear_log();
  }
  unsigned reads() const {
    unsigned n = 0;
    for (const auto& a : device.log()) n += a.write ? 0u : 1u;
    return n;
  }
  // Every writable register on the chip equals the driver's shadow (implemented bits).
  bool chip_matches_shadows() const {
    for (const auto& r : chip::kRegisters) {
      if (!chip::writable(r.access)) continue;
      const std::uint32_t m = chip::implemented_mask(r.reg);
      if ((device.chip_register(r.reg) & m) != (driver.shadow(r.reg) & m)) return false;
    }
    return true;
  }
};

}  // namespace tmc_test
