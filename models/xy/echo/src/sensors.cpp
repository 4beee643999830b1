// The two I2C sensors as the board runs them (docs/sensors.md "What the board does on an I2C
// error", "On the board (core/xy/board)", "Rotation: integration and wrap"): configured at the
// end of the boot, the gyro read every tick and the TMP117 every 250th, misses counted, a lost
// part retried, a foreign one never, each loss latched as fault 5000 / 6000 + the error. The
// model predicts from the device models' answers (Env::sensors) what the board reads and
// reports, never from the board's own temperature or angle (docs/echo-model.md).
#include "models/xy/echo/echo_model.hpp"

#include <cstdint>

#include "rounding.hpp"

namespace ap::model::xy_echo {
namespace {

// docs/sensors.md "What the board does on an I2C error" and "Fault codes".
constexpr std::int32_t kFaultTemperature = 5000;
constexpr std::int32_t kFaultGyro = 6000;
constexpr std::int32_t kErrWrongDevice = 4;        // WrongDeviceId / WrongDevice
constexpr std::int32_t kErrNoConversionYet = 7;
constexpr std::uint32_t kTempPeriodTicks = 250;    // one read per 250 ms conversion
constexpr std::uint32_t kTempMisses = 3;
constexpr std::uint32_t kTempRetryTicks = 1000;
constexpr std::uint32_t kGyroMisses = 10;
constexpr std::uint32_t kGyroRetryTicks = 100;
constexpr std::int64_t kGyroLsbPerDps = 131;       // ±250 °/s (DS-000169 Table 1)

// The typed error a bus outcome becomes (docs/sensors.md "The I2C port"): AddressNack 1,
// DataNack 2, BusError 3.
std::int32_t bus_error(ap::xy_i2c::Status s) {
  switch (s) {
    case ap::xy_i2c::Status::AddressNack: return 1;
    case ap::xy_i2c::Status::DataNack: return 2;
    case ap::xy_i2c::Status::NoPort: return 0;
    case ap::xy_i2c::Status::Ok:
    case ap::xy_i2c::Status::BusError: break;
  }
  return 3;
}

}  // namespace

void EchoModel::configure_temperature(const Sensors& s) {
  const SensorDevice& d = s.tmp117;
  if (d.answers == ap::xy_i2c::Status::NoPort) {  // no sensor bus: not driven, no fault
    temp_mode_ = SensorMode::Unwired;
    return;
  }
  if (d.answers != ap::xy_i2c::Status::Ok) {
    temp_mode_ = SensorMode::Lost;
    fault_ = kFaultTemperature + bus_error(d.answers);
  } else if (!d.identity_ok) {
    temp_mode_ = SensorMode::Foreign;
    fault_ = kFaultTemperature + kErrWrongDevice;
  } else {
    temp_mode_ = SensorMode::Ok;
    temp_misses_ = 0;
  }
}

void EchoModel::configure_gyro(const Sensors& s) {
  const SensorDevice& d = s.gyro;
  if (d.answers == ap::xy_i2c::Status::NoPort) {
    gyro_mode_ = SensorMode::Unwired;
    return;
  }
  if (d.answers != ap::xy_i2c::Status::Ok) {
    gyro_mode_ = SensorMode::Lost;
    fault_ = kFaultGyro + bus_error(d.answers);
  } else if (!d.identity_ok) {
    gyro_mode_ = SensorMode::Foreign;
    fault_ = kFaultGyro + kErrWrongDevice;
  } else {
    gyro_mode_ = SensorMode::Ok;
    gyro_misses_ = 0;
    gyro_held_ = 0;
  }
}

// After the axes stepped, before the echoes (docs/board.md "One cycle"): the gyro every tick,
// then the TMP117 once per conversion period; a lost sensor only retries its configure().
void EchoModel::sensors_tick() {
  const Sensors& s = env_.sensors;
  if (gyro_mode_ == SensorMode::Lost) {
    if (ticks_ % kGyroRetryTicks == 0) configure_gyro(s);
  } else if (gyro_mode_ == SensorMode::Ok) {
    if (s.gyro.answers == ap::xy_i2c::Status::Ok) {
      gyro_misses_ = 0;
      gyro_held_ = s.gyro_z;
      gyro_sum_ += s.gyro_z;
    } else if (++gyro_misses_ >= kGyroMisses) {
      gyro_mode_ = SensorMode::Lost;  // the angle stops; nothing integrated in this tick
      fault_ = kFaultGyro + bus_error(s.gyro.answers);
    } else {
      gyro_sum_ += gyro_held_;  // a failed read holds the last good sample
    }
  }
  if (temp_mode_ == SensorMode::Lost) {
    if (ticks_ % kTempRetryTicks == 0) configure_temperature(s);
  } else if (temp_mode_ == SensorMode::Ok && ticks_ % kTempPeriodTicks == 0) {
    std::int32_t err = 0;
    if (s.tmp117.answers != ap::xy_i2c::Status::Ok) {
      err = bus_error(s.tmp117.answers);
    } else if (s.temp_result == 0x8000) {
      err = kErrNoConversionYet;  // -256 °C: the reset code, no conversion finished
    } else {
      // 7.8125 m°C per LSB = 1000/128, two's complement, nearest m°C, halves away from zero.
      temperature_mc_ = static_cast<std::int32_t>(
          div_round_nearest(static_cast<std::int64_t>(static_cast<std::int16_t>(s.temp_result)) * 1000, 128));
      temp_misses_ = 0;
    }
    if (err != 0 && ++temp_misses_ >= kTempMisses) {
      temp_mode_ = SensorMode::Lost;
      fault_ = kFaultTemperature + err;
    }
  }
}

std::int32_t EchoModel::rotation_mdeg() const {
  // floor(sum / 131) m°, as a whole-turn remainder in [0, 360000).
  const std::int64_t mdeg = div_floor(gyro_sum_, kGyroLsbPerDps);
  return static_cast<std::int32_t>(((mdeg % 360000) + 360000) % 360000);
}

}  // namespace ap::model::xy_echo
