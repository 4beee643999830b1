#pragma once
// TMP117 driver: identify, configure, read. No heap, no exceptions, no floating point; every
// failure is a typed Error and leaves the driver as it was (docs/sensors.md).
#include <cstdint>

#include "core/xy/i2c/port.hpp"
#include "core/result/result.hpp"
#include "core/xy/tmp117/convert.hpp"
#include "core/xy/tmp117/registers.hpp"

namespace ap::xy_tmp117 {

enum class Error : std::uint8_t {
  NoPort,           // no I2C transfer function wired
  AddressNack,      // the sensor did not answer its address (absent, unpowered, wrong strap)
  DataNack,         // the sensor refused a byte
  BusError,         // the controller gave up (arbitration, stuck bus, timeout)
  WrongDeviceId,    // something answers at the address, but Device_ID is not a TMP117
  ConfigMismatch,   // Configuration read back differently from what was written
  NotConfigured,    // read before a successful configure(); nothing was sent
  NoConversionYet,  // Temp_Result still holds its reset code 0x8000 (datasheet 8.1.1)
};

template <class T>
using Result = ap::Result<T, Error>;

// The configuration this driver writes (docs/sensors.md "TMP117: conversion"): continuous
// conversion (MOD = 00), 8 averages (AVG = 01), CONV = 010: one result every 250 ms, of
// which 125 ms are the active conversion (datasheet Table 7-7). Alert mode, active-low ALERT
// pin on the alert flags: the board does not use the pin.
inline constexpr std::uint16_t kConfigWord = cfg::make(cfg::kModContinuous, 2, 1);
inline constexpr std::uint32_t kConversionPeriodMs = 250;

class Driver {
 public:
  explicit Driver(xy_i2c::Port port, std::uint8_t address = kAddressGnd) : port_(port), address_(address) {}

  // Reads Device_ID (DID must be 0x117; nothing is written to anything else), writes
  // kConfigWord and reads it back. Returns the silicon revision nibble.
  Result<std::uint8_t> configure();

  // One read of Temp_Result, in m°C (convert.hpp). NoConversionYet while the sensor still
  // shows its reset code: the first result appears one active conversion after configure.
  Result<std::int32_t> read_mc();

  bool configured() const { return configured_; }
  std::uint8_t revision() const { return revision_; }
  std::uint8_t address() const { return address_; }

 private:
  xy_i2c::Port port_;
  std::uint8_t address_;
  bool configured_ = false;
  std::uint8_t revision_ = 0;
};

}  // namespace ap::xy_tmp117
