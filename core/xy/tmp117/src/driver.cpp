#include "core/xy/tmp117/driver.hpp"

#include "core/xy/i2c/registers.hpp"

namespace ap::xy_tmp117 {

Result<std::uint8_t> Driver::configure() {
  std::uint16_t id = 0;
  auto s = xy_i2c::read_u16be(port_, address_, reg_address(Reg::DeviceId), id);
  if (s != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(s);
  // Checked before any write: a different device at this address must not get our config.
  if ((id & kDeviceIdMask) != kDeviceId) return Error::WrongDeviceId;

  s = xy_i2c::write_u16be(port_, address_, reg_address(Reg::Configuration), kConfigWord);
  if (s != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(s);
  std::uint16_t back = 0;
  s = xy_i2c::read_u16be(port_, address_, reg_address(Reg::Configuration), back);
  if (s != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(s);
  // Status bits 15:12 (Data_Ready may already be set) are not ours to compare.
  if ((back & cfg::kWritable) != kConfigWord) return Error::ConfigMismatch;

  configured_ = true;
  revision_ = static_cast<std::uint8_t>(id >> kRevisionShift);
  return revision_;
}

Result<std::int32_t> Driver::read_mc() {
  if (!configured_) return Error::NotConfigured;
  std::uint16_t code = 0;
  const auto s = xy_i2c::read_u16be(port_, address_, reg_address(Reg::TempResult), code);
  if (s != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(s);
  // -256 °C is outside the sensor's range (-55..150 °C), so this code only ever means "reset,
  // no conversion finished yet" and must not reach the PC as a temperature.
  if (code == kResetTempResult) return Error::NoConversionYet;
  return millicelsius(code);
}

}  // namespace ap::xy_tmp117
