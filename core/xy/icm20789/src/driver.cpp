#include "core/xy/icm20789/driver.hpp"

#include <array>

#include "core/xy/i2c/registers.hpp"

namespace ap::xy_icm20789 {

xy_i2c::Status Driver::update(std::uint8_t reg, std::uint8_t mask, std::uint8_t value, bool& matches) {
  std::uint8_t old = 0;
  auto s = xy_i2c::read_u8(port_, address_, reg, old);
  if (s != xy_i2c::Status::Ok) return s;
  const auto next = static_cast<std::uint8_t>((old & ~mask) | (value & mask));
  s = xy_i2c::write_u8(port_, address_, reg, next);
  if (s != xy_i2c::Status::Ok) return s;
  std::uint8_t back = 0;
  s = xy_i2c::read_u8(port_, address_, reg, back);
  if (s != xy_i2c::Status::Ok) return s;
  matches = ((back ^ value) & mask) == 0;
  return s;
}

Result<FullScale> Driver::configure(FullScale fs) {
  std::uint8_t who = 0;
  const auto s = xy_i2c::read_u8(port_, address_, reg::kWhoAmI, who);
  if (s != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(s);
  if (who != kWhoAmIValue) return Error::WrongDevice;

  struct Step {
    std::uint8_t reg, mask, value;
  };
  // Waking first: the other registers are written to a running chip, as the datasheet's
  // start-up sequence does. DEVICE_RESET stays 0 in the mask's value.
  const std::array<Step, 4> steps{{
      {reg::kPwrMgmt1, 0xFF, kPwrMgmt1Value},
      {reg::kSmplrtDiv, 0xFF, kSmplrtDiv},
      {reg::kConfig, 0x7F, kDlpfCfg},
      {reg::kGyroConfig, 0xFB,
       static_cast<std::uint8_t>(static_cast<unsigned>(fs) << bits::kFsSelShift)},
  }};
  for (const auto& st : steps) {
    bool matches = false;
    const auto u = update(st.reg, st.mask, st.value, matches);
    if (u != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(u);
    if (!matches) return Error::ConfigMismatch;
  }
  configured_ = true;
  fs_ = fs;
  return fs;
}

Result<std::int16_t> Driver::read_rate_z() {
  if (!configured_) return Error::NotConfigured;
  std::array<std::uint8_t, 2> b{};
  const auto s = xy_i2c::read_burst(port_, address_, reg::kGyroZoutH, b);
  if (s != xy_i2c::Status::Ok) return xy_i2c::error_of<Error>(s);
  return static_cast<std::int16_t>(static_cast<std::uint16_t>((unsigned{b[0]} << 8) | b[1]));
}

}  // namespace ap::xy_icm20789
