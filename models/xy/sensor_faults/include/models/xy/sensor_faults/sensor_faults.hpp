// An independent reference of the XY board's I2C sensor fault rules: what the board's
// temperature and rotation show, and what state each sensor is in, tick by tick, given how
// the bus answers each part. Written from docs/sensors.md ("What the board does on an I2C
// error", "On the board" and its "Decisions beyond the list above") and the datasheet facts
// that page cites (TI SNOSD82D, TDK DS-000169), never from core/xy/board: every number below is
// restated from the docs, none is taken from the firmware's constants. The oracle of
// properties/xy/board/board_sensor_faults_oracle_test.cpp.
//
// Scope: a board built with its sensor bus (no Unwired state), the TMP117 set up as the docs
// say (a result every 250 ms) and the gyro at its ±250 °/s full scale. The register-level
// conversions are checked elsewhere (tmp117_convert, icm20789_rotation); here a TMP117 result
// is given already in m°C and a gyro sample as its raw GYRO_ZOUT code.
#pragma once

#include <cstdint>
#include <optional>

namespace ap::model::xy_sensor_faults {

// ---- Numbers, each from docs/sensors.md ---------------------------------------------------
// "Conversion and averaging": CONV = 010, AVG = 01 give one result every 250 ms (SNOSD82D
// Table 7-7); "On the board": the TMP117 is read at ticks() % 250 == 0.
inline constexpr std::uint64_t kTemperatureReadPeriod = 250;
// "What the board does on an I2C error": three periods in a row without a good reading latch.
inline constexpr std::uint32_t kTemperatureMissesToLatch = 3;
// Same section: once Lost, configure() is retried once per second (ticks() % 1000 == 0).
inline constexpr std::uint64_t kTemperatureRetryPeriod = 1000;
// Same section: after 10 failed gyro ticks in a row the angle is no longer trusted.
inline constexpr std::uint32_t kGyroMissesToLatch = 10;
// Same section: once Lost, the gyro's configure() is retried every 100 ms (ticks() % 100 == 0).
inline constexpr std::uint64_t kGyroRetryPeriod = 100;
// "Fault codes": 5000 + xy_tmp117::Error, 6000 + xy_icm20789::Error, numbered 1 AddressNack,
// 2 DataNack, 3 BusError, 4 WrongDeviceId / WrongDevice, 7 NoConversionYet.
inline constexpr std::int32_t kTemperatureFaultBase = 5000;
inline constexpr std::int32_t kGyroFaultBase = 6000;
inline constexpr std::int32_t kErrorForeign = 4;
inline constexpr std::int32_t kErrorNoConversionYet = 7;
// "Before the first reading": Temp_Result's reset code, -256 °C (SNOSD82D §8.1.1).
inline constexpr std::int32_t kNoTemperatureMc = -256000;
// docs/protocol.md's subscriber ranges (quoted in docs/sensors.md "What the seed says", G22):
// temperature -99999..999999 m°C, clamped, never wrapped ("Wire range").
inline constexpr std::int32_t kWireTemperatureMin = -99999;
inline constexpr std::int32_t kWireTemperatureMax = 999999;
// "Rotation: integration and wrap": at ±250 °/s one LSB is 1/131 °/s (DS-000169: 131
// LSB/(°/s)), so one sample per 1 ms tick turns the platform by code / 131 m°; the angle is
// exact in 1/131 m° and floors into [0, 359999] m°.
inline constexpr std::int64_t kGyroLsbPerDps = 131;
inline constexpr std::int64_t kMdegPerTurn = 360000;

// How every transaction to one part ends in a tick (docs/sensors.md "The I2C port"; an
// absent part does not acknowledge its address, a stuck bus fails everything its own way).
enum class Answer : std::uint8_t { Ok, AddressNack, DataNack, BusError };

// "On the board" table: Ok, Lost (latched, retried), Foreign (latched, never retried).
enum class State : std::uint8_t { Ok, Lost, Foreign };

struct TemperaturePart {
  Answer answer = Answer::Ok;
  bool genuine = true;  // Device_ID's DID[11:0] is 0x117 (SNOSD82D §8)
  // What Temp_Result converts to when read, in m°C; nullopt: it still holds its reset code
  // 0x8000, which the driver reports as NoConversionYet ("read_mc()").
  std::optional<std::int32_t> result_mc = 25000;
};

struct GyroPart {
  Answer answer = Answer::Ok;
  bool genuine = true;    // WHO_AM_I reads 0x03 (DS-000169)
  std::int16_t code = 0;  // GYRO_ZOUT, the z rate sample a read returns
};

// How both parts answer during one tick (or during boot()).
struct World {
  TemperaturePart temperature;
  GyroPart gyro;
};

class Board {
 public:
  // Power-up: both sensors configured ("On the board": boot() configures both), tick count 0.
  void boot(const World& w);
  // The PC's `clear` (docs/board.md G12): handled in the cycle's receive step, before the
  // sensors (docs/board.md "One cycle", steps 3 and 7).
  void clear_fault() { fault_ = 0; }
  // One 1 ms tick's sensor step (docs/board.md "One cycle", step 7).
  void tick(const World& w);

  State temperature_state() const { return temperature_; }
  State gyro_state() const { return gyro_; }
  // The latched sensor FAULT code, 0 when none (the model knows no other fault source).
  std::int32_t fault_code() const { return fault_; }
  // The last good temperature, kNoTemperatureMc before the first.
  std::int32_t temperature_mc() const { return temperature_mc_; }
  // What the temperature subscriber sends: the last good temperature clamped to the wire.
  std::int32_t temperature_subscriber() const;
  // What the rotation subscriber sends, in [0, 359999] m°.
  std::int32_t rotation_mdeg() const;
  std::uint64_t ticks() const { return ticks_; }

 private:
  void configure_temperature(const TemperaturePart& p);
  void configure_gyro(const GyroPart& g);
  void gyro_step(const GyroPart& g);
  void temperature_step(const TemperaturePart& p);

  std::uint64_t ticks_ = 0;
  State temperature_ = State::Ok;
  State gyro_ = State::Ok;
  std::int32_t fault_ = 0;
  std::uint32_t temperature_misses_ = 0;  // periods in a row without a good reading
  std::uint32_t gyro_misses_ = 0;         // failed reads in a row
  std::int32_t temperature_mc_ = kNoTemperatureMc;
  std::int16_t held_ = 0;   // the sample a failed gyro read integrates
  std::int64_t codes_ = 0;  // the unwrapped sum of integrated samples
};

}  // namespace ap::model::xy_sensor_faults
