#pragma once
// ICM-20789 gyroscope driver: identify, wake and configure, read the z-rate. No heap, no
// exceptions, no floating point; every failure is a typed Error and leaves the driver as it
// was (docs/sensors.md).
#include <cstdint>

#include "core/xy/i2c/port.hpp"
#include "core/result/result.hpp"
#include "core/xy/icm20789/registers.hpp"
#include "core/xy/icm20789/rotation.hpp"

namespace ap::xy_icm20789 {

enum class Error : std::uint8_t {
  NoPort,          // no I2C transfer function wired
  AddressNack,     // the sensor did not answer its address
  DataNack,        // the sensor refused a byte
  BusError,        // the controller gave up (arbitration, stuck bus, timeout)
  WrongDevice,     // something answers at the address, but WHO_AM_I is not 0x03
  ConfigMismatch,  // a configuration field read back differently from what was written
  NotConfigured,   // read before a successful configure(); nothing was sent
};

template <class T>
using Result = ap::Result<T, Error>;

// What configure() writes (docs/sensors.md "ICM-20789: configuration"):
// PWR_MGMT_1: SLEEP = 0, CLKSEL = 1 (PLL when ready, the datasheet's choice for full gyro
// performance). CONFIG: DLPF_CFG = 2 (92 Hz bandwidth, 3.9 ms delay, 1 kHz internal rate),
// EXT_SYNC_SET = 0, FIFO_MODE = 0. SMPLRT_DIV = 0: 1 kHz output rate, one new sample per 1 ms
// control tick. GYRO_CONFIG: FS_SEL as asked, FCHOICE_B = 00 (the DLPF in the path), no
// self-test. Reserved bits are kept as the chip has them.
inline constexpr std::uint8_t kPwrMgmt1Value = 0x01;
inline constexpr std::uint8_t kDlpfCfg = 2;
inline constexpr std::uint8_t kSmplrtDiv = 0;

class Driver {
 public:
  explicit Driver(xy_i2c::Port port, std::uint8_t address = kAddressAd0Low) : port_(port), address_(address) {}

  // WHO_AM_I first (nothing is written to a device that is not an ICM-20789), then wake and
  // configure as above, each register verified by reading it back.
  Result<FullScale> configure(FullScale fs = FullScale::Dps250);

  // GYRO_ZOUT_H / _L in one burst (so the halves belong to the same sample): raw z-rate,
  // sensitivity per full_scale().
  Result<std::int16_t> read_rate_z();

  bool configured() const { return configured_; }
  FullScale full_scale() const { return fs_; }
  std::uint8_t address() const { return address_; }

 private:
  // Read-modify-write of the bits in `mask`, then read back and compare those bits.
  xy_i2c::Status update(std::uint8_t reg, std::uint8_t mask, std::uint8_t value, bool& matches);

  xy_i2c::Port port_;
  std::uint8_t address_;
  bool configured_ = false;
  FullScale fs_ = FullScale::Dps250;
};

}  // namespace ap::xy_icm20789
