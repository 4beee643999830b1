// The I2C sensors on the board (docs/sensors.md "On the board (core/xy/board)", "What the
// board does on an I2C error"), apart from the motion because neither sensor ever stops it:
// the TMP117 and the ICM-20789 configured at the end of the boot, the gyro read every tick and
// integrated, the TMP117 read once per conversion, misses counted, a lost part retried and a
// foreign one never, each loss latched as a fault; then the charger enable from the
// temperature (docs/board.md "Charger disconnect").
// After the axes: an I2C transaction may take a few hundred microseconds, and the step
// outputs of the tick must not wait for it. Before the echoes, so they carry this tick's
// angle and any fault a sensor latched in it.
#include "core/xy/board/board.hpp"

namespace ap::xy_board {

void Board::configure_temperature() {
  const auto r = tmp117_.configure();
  if (r) {
    sensors_.temperature = SensorState::Ok;
    sensors_.temperature_misses = 0;
    return;
  }
  // No transfer function: a board built without the sensor bus, as any Hardware part may be.
  if (r.error() == xy_tmp117::Error::NoPort) {
    sensors_.temperature = SensorState::Unwired;
    return;
  }
  ++sensors_.temperature_errors;
  // A foreign part at the address is never written again (docs/sensors.md): rewriting it
  // blindly is worse than having no temperature.
  sensors_.temperature = r.error() == xy_tmp117::Error::WrongDeviceId ? SensorState::Foreign : SensorState::Lost;
  fault_ = kFaultTemperature + static_cast<std::int32_t>(r.error());
}

void Board::configure_gyro() {
  const auto r = gyro_.configure(xy_icm20789::FullScale::Dps250);
  if (r) {
    sensors_.gyro = SensorState::Ok;
    sensors_.gyro_misses = 0;
    // A sample from before an outage says nothing about the rate after it.
    gyro_held_ = 0;
    return;
  }
  if (r.error() == xy_icm20789::Error::NoPort) {
    sensors_.gyro = SensorState::Unwired;
    return;
  }
  ++sensors_.gyro_errors;
  sensors_.gyro = r.error() == xy_icm20789::Error::WrongDevice ? SensorState::Foreign : SensorState::Lost;
  fault_ = kFaultGyro + static_cast<std::int32_t>(r.error());
}

void Board::read_sensors() {
  read_gyro();
  read_temperature();
  const bool allowed = xy_board::charging_allowed(charging_, sensors_.temperature_valid, temperature_mc_);
  if (allowed != charging_ || !charging_told_) {
    charging_ = allowed;
    charging_told_ = true;
    if (hw_.charger_enable != nullptr) hw_.charger_enable(hw_.ctx, allowed);
  }
}

void Board::read_gyro() {
  if (sensors_.gyro == SensorState::Lost) {
    // The angle is no longer trusted and stays where it stopped; a recovered chip continues
    // from there (the PC may re-reference it).
    if (ticks_ % kGyroRetryPeriod == 0) configure_gyro();
    return;
  }
  if (sensors_.gyro != SensorState::Ok) return;
  const auto r = gyro_.read_rate_z();
  if (r) {
    sensors_.gyro_misses = 0;
    gyro_held_ = *r;
    rotation_.step(*r);
    return;
  }
  ++sensors_.gyro_errors;
  if (++sensors_.gyro_misses >= kGyroMissLimit) {
    sensors_.gyro = SensorState::Lost;
    fault_ = kFaultGyro + static_cast<std::int32_t>(r.error());
    return;
  }
  // One sample per tick (1 kHz behind the 92 Hz filter): the previous one is the best
  // estimate of the missing one.
  rotation_.step(gyro_held_);
}

void Board::read_temperature() {
  if (sensors_.temperature == SensorState::Lost) {
    if (ticks_ % kTemperatureRetryPeriod == 0) configure_temperature();
    return;
  }
  // One read per conversion (250 ms, docs/sensors.md "Conversion and averaging").
  if (sensors_.temperature != SensorState::Ok || ticks_ % kTemperaturePeriod != 0) return;
  const auto r = tmp117_.read_mc();
  if (r) {
    sensors_.temperature_misses = 0;
    sensors_.temperature_valid = true;
    temperature_mc_ = *r;
    return;
  }
  // NoConversionYet counts like a bus error: either way there is no temperature this period.
  ++sensors_.temperature_errors;
  if (++sensors_.temperature_misses >= kTemperatureMissLimit) {
    sensors_.temperature = SensorState::Lost;
    fault_ = kFaultTemperature + static_cast<std::int32_t>(r.error());
  }
}

}  // namespace ap::xy_board
