// TMP117 properties: the driver reads back what the modelled sensor measured to within half
// an LSB plus the m°C rounding, any conversion matches the exact fraction, and any single bus
// failure during configure() or a read is typed, leaves the driver unchanged and is healed by
// the next call on a good bus.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cstdlib>
#include <vector>

#include "core/xy/tmp117/driver.hpp"
#include "models/xy/i2c/bus.hpp"
#include "models/xy/tmp117/device.hpp"
#include "reference.hpp"

namespace {

namespace chip = ap::xy_tmp117;
namespace bus = ap::xy_i2c;
using ap::model::xy_i2c::Bus;

// The bus fault each error names (docs/sensors.md), written out here rather than taken from the
// driver under test.
chip::Error expected_error(ap::xy_i2c::Status s) {
  switch (s) {
    case ap::xy_i2c::Status::NoPort: return chip::Error::NoPort;
    case ap::xy_i2c::Status::AddressNack: return chip::Error::AddressNack;
    case ap::xy_i2c::Status::DataNack: return chip::Error::DataNack;
    default: return chip::Error::BusError;
  }
}
using ap::model::xy_tmp117::Device;

struct Bench {
  Device device;
  Bus bus;
  chip::Driver driver{bus.port()};
  Bench() { bus.attach(device); }
};

rc::Gen<bus::Status> gen_fault() {
  return rc::gen::element(bus::Status::AddressNack, bus::Status::DataNack, bus::Status::BusError);
}

RC_GTEST_PROP(tmp117_props, reads_what_the_sensor_measured, ()) {
  Bench b;
  RC_ASSERT(b.driver.configure());
  // The sensor's specified range (datasheet 6.3) and beyond, to the register's limits.
  const auto mc = *rc::gen::oneOf(rc::gen::inRange<std::int32_t>(-55000, 150001),
                                  rc::gen::inRange<std::int32_t>(-255990, 255990));
  b.device.set_temperature_mc(mc);
  b.device.advance_ms(*rc::gen::inRange<std::uint64_t>(125, 5000));
  const auto t = b.driver.read_mc();
  RC_ASSERT(t);
  // 1/2 LSB = 3.90625 m°C of quantisation plus 1/2 m°C of rounding.
  RC_ASSERT(std::abs(*t - mc) <= 4);
  RC_ASSERT(*t == tmp117_test::reference_mc(b.device.reg(chip::Reg::TempResult)));
}

RC_GTEST_PROP(tmp117_props, conversion_is_the_exact_fraction_rounded, (std::uint16_t code)) {
  RC_ASSERT(chip::millicelsius(code) == tmp117_test::reference_mc(code));
}

RC_GTEST_PROP(tmp117_props, one_bus_failure_anywhere_is_typed_and_healed, ()) {
  Bench b;
  const bool configured_first = *rc::gen::arbitrary<bool>();
  if (configured_first) {
    RC_ASSERT(b.driver.configure());
    b.device.advance_ms(125);
  }
  const auto status = *gen_fault();
  const auto at = *rc::gen::inRange(0u, 3u);
  b.bus.fail_at(at, status);
  const bool do_read = configured_first && *rc::gen::arbitrary<bool>();
  if (do_read) {
    const auto r = b.driver.read_mc();
    if (at == 0) {
      RC_ASSERT(!r);
      RC_ASSERT(r.error() == expected_error(status));
    } else {
      RC_ASSERT(r);
    }
    RC_ASSERT(b.driver.configured());
  } else {
    const auto r = b.driver.configure();
    RC_ASSERT(!r);
    RC_ASSERT(r.error() == expected_error(status));
    RC_ASSERT(b.driver.configured() == configured_first);
  }
  b.bus.heal();
  RC_ASSERT(b.driver.configure());
  b.device.advance_ms(125);
  RC_ASSERT(b.driver.read_mc());
}

}  // namespace
