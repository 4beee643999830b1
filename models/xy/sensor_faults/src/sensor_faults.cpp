// The XY board's I2C sensor fault rules, from docs/sensors.md (sections named at each rule).
#include "models/xy/sensor_faults/sensor_faults.hpp"

#include <algorithm>

namespace ap::model::xy_sensor_faults {

namespace {

// "Fault codes": the errors numbered as declared, 1 AddressNack, 2 DataNack, 3 BusError.
std::int32_t error_of(Answer a) {
  switch (a) {
    case Answer::AddressNack:
      return 1;
    case Answer::DataNack:
      return 2;
    case Answer::BusError:
      return 3;
    case Answer::Ok:
      break;
  }
  return 0;
}

}  // namespace

void Board::boot(const World& w) {
  *this = Board{};
  configure_temperature(w.temperature);
  configure_gyro(w.gyro);
}

// "On the board": configure() checks the identity first; a foreign part is Foreign, latched
// and never retried; any other failure is Lost with its error ("a failed configure() at
// boot" latches too). A good configure() is Ok and, by "Decisions beyond the list above"
// ("A good configure() starts the count anew"), begins a new row of misses.
void Board::configure_temperature(const TemperaturePart& p) {
  if (p.answer != Answer::Ok) {
    temperature_ = State::Lost;
    fault_ = kTemperatureFaultBase + error_of(p.answer);
    return;
  }
  if (!p.genuine) {
    temperature_ = State::Foreign;
    fault_ = kTemperatureFaultBase + kErrorForeign;
    return;
  }
  temperature_ = State::Ok;
  temperature_misses_ = 0;
}

// As above, and "The held sample is reset to 0 at every good configure()": a sample from
// before an outage says nothing about the rate after it.
void Board::configure_gyro(const GyroPart& g) {
  if (g.answer != Answer::Ok) {
    gyro_ = State::Lost;
    fault_ = kGyroFaultBase + error_of(g.answer);
    return;
  }
  if (!g.genuine) {
    gyro_ = State::Foreign;
    fault_ = kGyroFaultBase + kErrorForeign;
    return;
  }
  gyro_ = State::Ok;
  gyro_misses_ = 0;
  held_ = 0;
}

// "Decisions beyond the list above", "One tick, gyro first": the gyro's step, then the
// TMP117's, so a TMP117 latch in the same tick is the later one and its code stays.
void Board::tick(const World& w) {
  ++ticks_;
  gyro_step(w.gyro);
  temperature_step(w.temperature);
}

// "What the board does on an I2C error", the ICM-20789 paragraph, and the "On the board"
// table's ICM-20789 column.
void Board::gyro_step(const GyroPart& g) {
  if (gyro_ == State::Foreign) return;  // latched, never read nor retried
  if (gyro_ == State::Lost) {
    // No reads, the angle stays; configure() at ticks() % 100 == 0. The configure tick reads
    // nothing ("The configure tick reads nothing"): reads start with the next tick.
    if (ticks_ % kGyroRetryPeriod == 0) configure_gyro(g);
    return;
  }
  if (g.answer == Answer::Ok) {
    // A good read: integrated as one 1 ms sample, and it ends the row of failed reads.
    codes_ += g.code;
    held_ = g.code;
    gyro_misses_ = 0;
    return;
  }
  // A failed read: "the 10th failed read in a row (it integrates nothing)" latches;
  // the 1st to 9th integrate the held sample.
  if (++gyro_misses_ == kGyroMissesToLatch) {
    gyro_ = State::Lost;
    fault_ = kGyroFaultBase + error_of(g.answer);
    return;
  }
  codes_ += held_;
}

// "What the board does on an I2C error", the TMP117 paragraph, and the "On the board" table's
// TMP117 column.
void Board::temperature_step(const TemperaturePart& p) {
  if (temperature_ == State::Foreign) return;
  if (temperature_ == State::Lost) {
    // Only configure() once a second; a good one reads next at the next multiple of 250
    // ("The configure tick reads nothing": tick 1000 is such a multiple but is not read).
    if (ticks_ % kTemperatureRetryPeriod == 0) configure_temperature(p);
    return;
  }
  if (ticks_ % kTemperatureReadPeriod != 0) return;  // one read per conversion
  std::int32_t error = 0;
  if (p.answer != Answer::Ok) {
    error = error_of(p.answer);
  } else if (!p.result_mc) {
    error = kErrorNoConversionYet;  // "NoConversionYet: a failed read (no temperature this period)"
  } else {
    // A good reading: shown from now on, and it ends the row of failed periods ("three
    // periods IN A ROW without a good reading").
    temperature_mc_ = *p.result_mc;
    temperature_misses_ = 0;
    return;
  }
  // A failed period keeps the last good value; the 3rd in a row latches with its error.
  if (++temperature_misses_ == kTemperatureMissesToLatch) {
    temperature_ = State::Lost;
    fault_ = kTemperatureFaultBase + error;
  }
}

std::int32_t Board::temperature_subscriber() const {
  return std::clamp(temperature_mc_, kWireTemperatureMin, kWireTemperatureMax);
}

// "Rotation: integration and wrap": the exact angle is (sum of codes) / 131 m°, floored and
// taken modulo a turn, so it wraps both ways (-1/131 m° reads 359999).
std::int32_t Board::rotation_mdeg() const {
  const std::int64_t turn = kMdegPerTurn * kGyroLsbPerDps;
  std::int64_t units = codes_ % turn;
  if (units < 0) units += turn;
  return static_cast<std::int32_t>(units / kGyroLsbPerDps);
}

}  // namespace ap::model::xy_sensor_faults
