// The board core: the main state machine of seed-000.md §4.7 (blocked / user control /
// parameter setting) tying the frame receive path, the callback table, both axes, the
// parameter store, the two TMC2130 drivers and the two I2C sensors (TMP117 board
// temperature, ICM-20789 platform rotation) together behind a narrow hardware interface.
//
// It is pure and deterministic: every input arrives through Hardware::sample(), the I2C
// port or uart_rx(), every output leaves through Hardware's function pointers, and time is the
// number of tick() calls (one per 1 ms control tick). The firmware, the simulated board,
// the tests and the fuzzers all drive this same class. docs/board.md has the cycle order
// and the decisions on the seed's gaps (G14-G16, G23, G24).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/axis/axis.hpp"
#include "core/xy/axis/position.hpp"
#include "core/xy/axis/units.hpp"
#include "core/xy/axis/watchdog.hpp"
#include "core/xy/frame/callback_table.hpp"
#include "core/xy/frame/frames.hpp"
#include "core/xy/frame/stream_framer.hpp"
#include "core/xy/i2c/port.hpp"
#include "core/xy/icm20789/driver.hpp"
#include "core/xy/icm20789/rotation.hpp"
#include "core/xy/path/executor.hpp"
#include "core/xy/board/charging.hpp"
#include "core/xy/board/led.hpp"
#include "core/xy/storage/store.hpp"
#include "core/xy/tmc2130/driver.hpp"
#include "core/xy/tmp117/driver.hpp"

namespace ap::xy_board {

using xy_frame::Axis;
inline constexpr std::size_t kAxes = 2;

// Everything the board reads at the start of a cycle. Levels, not edges: the board keeps
// its own memory (endstop latches live in the axis state, battery hysteresis here). The
// temperature and the rotation are not here: the board reads them itself over the I2C port
// (docs/sensors.md).
struct Inputs {
  std::array<std::uint8_t, kAxes> endstop_min{};  // 1 = Hall switch active
  std::array<std::uint8_t, kAxes> endstop_max{};
  bool usb = false;      // the manually set USB flag of the prototype (G23)
  bool charger = false;  // charger connected
  std::uint16_t battery_mv = 4000;
  std::int32_t charge_ma = 0;
  bool ble_status1 = false;  // STATUS1_IND, STATUS2_IND (Tab. 7-2): (0,1) = Data Session open
  bool ble_status2 = true;
  std::array<xy_axis::EncoderReading, kAxes> encoder{};
  // The user button's off request (thesis §7.9.5: the button's own controller asks the MCU to
  // switch off and lets it run a shutdown sequence first); 1 = requested.
  bool button = false;
};

// What drives one axis's STEP/DIR/ENA pins for the coming tick: `steps` rising STEP edges at
// `step_hz` (the timer setting is xy_axis::step_timer(step_hz)), all with DIR = `dir`.
struct MotorOutput {
  bool enable = true;
  std::int8_t dir = 1;
  std::int32_t steps = 0;
  std::uint32_t step_hz = 0;
};

// The hardware boundary. Plain function pointers with one context, so the core needs no
// virtual interface; any pointer may be null (that output is then simply not driven).
struct Hardware {
  void* ctx = nullptr;
  std::array<xy_tmc2130::SpiPort, kAxes> tmc{};  // one chip select per driver
  xy_storage::SpiBus fram{nullptr, nullptr};
  // The sensor bus: TMP117 at 0x48 and ICM-20789 at 0x68 (docs/sensors.md). Without a
  // transfer function the board was built without the sensors: they are not driven, and no
  // fault is raised for them.
  xy_i2c::Port i2c{};
  void (*sample)(void* ctx, Inputs& in) = nullptr;
  void (*motor)(void* ctx, Axis axis, const MotorOutput& out) = nullptr;
  void (*uart_tx)(void* ctx, std::span<const std::uint8_t> bytes) = nullptr;
  // The RGB LED at the end of every tick: the colour lit now (Off in a blink's dark half),
  // from Tab. 7-4 (core/xy/board/led.hpp).
  void (*led)(void* ctx, LedColour lit) = nullptr;
  // Programs an axis's absolute encoder (RLS Orbis: position offset and multi-turn counter, in
  // its own memory) so that where it stands now reads `counts` = turns * 16384 + angle from
  // then on. Called once per completed homing (docs/motion.md "Homing and the encoder zero").
  void (*encoder_zero)(void* ctx, Axis axis, std::int64_t counts) = nullptr;
  // The KillSwitch pin (thesis §7.9.5): cuts the unit's own supply. Called once, at the end of
  // the shutdown sequence an off request started (docs/board.md "Button and shutdown").
  void (*power_off)(void* ctx) = nullptr;
  // The charging circuit's enable (thesis §7.9.3): called at the first tick and on every
  // change (core/xy/board/charging.hpp).
  void (*charger_enable)(void* ctx, bool on) = nullptr;
  // Each frame that takes a new seq (docs/protocol.md "Delivery": executed, or answered as
  // blocked), once, in order: a trace point for loggers and for the harness's exactly-once check.
  void (*frame_taken)(void* ctx, const xy_frame::CommandFrame& f) = nullptr;
};

enum class MainState : std::uint8_t { Blocked, UserControl, ParamSet };
enum class Block : std::uint8_t { None, Usb, Charger, Battery };

// Why the last completed motion of an axis ended; shown in the echo while it stands still.
enum class AxisEvent : std::uint8_t { None, Reached, StoppedByUser, Endstop, LinkLost, HomeFailed };

// Counters wrap at 2^32 (13 years of 10 frames/s).
struct BoardCounters {
  xy_frame::FramerCounters framer{};
  std::uint32_t dispatched_frames = 0;  // accepted, session open, not blocked: handlers ran
  std::uint32_t gated_frames = 0;       // accepted while the BLE session was not open: dropped
  std::uint32_t repeated_frames = 0;    // the seq of the last frame taken again: answered, not run
  std::uint32_t older_frames = 0;       // a seq older than the last frame taken: answered, not run
  std::uint32_t blocked_frames = 0;     // accepted while blocked: answered, not dispatched
  std::uint32_t unhandled_frames = 0;
  std::uint32_t refused_parts = 0;
  std::uint32_t watchdog_expiries = 0;
  std::uint32_t rx_overruns = 0;  // bytes dropped because the receive ring was full
  std::uint32_t echoes_sent = 0;
  friend constexpr bool operator==(const BoardCounters&, const BoardCounters&) = default;
};

// Fault codes shown as the data of a FAULT echo: source * 1000 + detail.
inline constexpr std::int32_t kFaultStorage = 1000;     // + xy_storage::StoreStatus
inline constexpr std::int32_t kFaultDriverX = 2000;     // + xy_tmc2130::Error
inline constexpr std::int32_t kFaultDriverY = 3000;     // + xy_tmc2130::Error
inline constexpr std::int32_t kFaultBadParams = 4000;   // loaded set does not convert: defaults used
inline constexpr std::int32_t kFaultTemperature = 5000; // + xy_tmp117::Error (docs/sensors.md)
inline constexpr std::int32_t kFaultGyro = 6000;        // + xy_icm20789::Error

inline constexpr std::uint8_t kHomingModeEndstop = 1;   // FRAM homing_mode: towards the min endstop
inline constexpr std::uint16_t kBatteryHysteresisMv = 100;  // G23: unblock at threshold + 100 mV
inline constexpr std::size_t kRxCapacity = 256;             // > 6 command frames
inline constexpr std::size_t kMaxEchoesPerCycle = 4;
inline constexpr std::uint32_t kDriverCheckPeriod = 100;    // ticks between GSTAT checks per driver

// The I2C sensors' schedule and error policy (docs/sensors.md "What the board does on an I2C
// error"): the TMP117 is read once per conversion period and its configure() retried once a
// second; the gyro is read every tick and retried every 100 ms.
inline constexpr std::uint32_t kTemperaturePeriod = xy_tmp117::kConversionPeriodMs;  // ticks
inline constexpr std::uint32_t kTemperatureMissLimit = 3;    // periods in a row without a reading
inline constexpr std::uint32_t kTemperatureRetryPeriod = 1000;
inline constexpr std::uint32_t kGyroMissLimit = 10;          // failed reads in a row
inline constexpr std::uint32_t kGyroRetryPeriod = 100;
// The temperature before the first good reading: Temp_Result's reset code (-256 °C, outside
// the sensor's -55..150 °C), which the subscriber clamps to the wire's -99999.
inline constexpr std::int32_t kNoTemperatureMc = xy_tmp117::kMinMilliCelsius;

// Unwired: Hardware::i2c has no transfer function. Ok: configured, read on schedule. Lost:
// failed, fault latched, configure() retried. Foreign: a different part answers at the
// address; latched and never written again.
enum class SensorState : std::uint8_t { Unwired, Ok, Lost, Foreign };

struct SensorStatus {
  SensorState temperature = SensorState::Unwired;
  SensorState gyro = SensorState::Unwired;
  bool temperature_valid = false;      // a good reading since power-up
  std::uint32_t temperature_misses = 0;  // periods in a row without a good reading
  std::uint32_t gyro_misses = 0;         // failed reads in a row
  std::uint32_t temperature_errors = 0;  // every failed configure or read, wrapping
  std::uint32_t gyro_errors = 0;
  friend constexpr bool operator==(const SensorStatus&, const SensorStatus&) = default;
};

struct BootResult {
  xy_storage::BootReport store;
  std::array<xy_axis::StartPosition, kAxes> start{};
  bool drivers_ok = false;
};

enum class ShutdownResult : std::uint8_t { Ok, Moving, StorageFault };

// Axis parameters in core units derived from a stored set (µm -> microsteps).
struct Derived {
  xy_axis::Mechanics mech{};
  std::array<xy_axis::Config, kAxes> cfg{};
  bool ok = false;
};
Derived derive(const xy_storage::ParameterSet& p);

class Board {
 public:
  explicit Board(const Hardware& hw);
  Board(const Board&) = delete;
  Board& operator=(const Board&) = delete;

  // Power-up (§4.6): load the parameters (newest valid A/B copy), initialise both drivers
  // with the stored currents and microsteps, seed each step counter from its encoder or the
  // saved counter, configure both I2C sensors. Call once before the first tick().
  BootResult boot();

  // The UART receive interrupt: bytes are only stored; the framer runs in tick().
  void uart_rx(std::span<const std::uint8_t> bytes);

  // One control cycle (1 ms). Order: sample inputs; begin-of-cycle checks (block causes,
  // BLE status); frames from the receive ring through framer -> gate -> callback table;
  // link watchdog; both axes stepped and their outputs driven; periodic driver check;
  // the I2C sensors (gyro every tick, temperature every 250); the echoes of this cycle built
  // and sent last, after the commands took effect.
  void tick();

  // Orderly shutdown: writes both step counters with the validity flag (only at rest).
  ShutdownResult shutdown();

  // Observers (tests, fuzz oracles, the simulated board's trace).
  MainState main_state() const { return main_state_; }
  Block block() const { return block_; }
  // Tab. 7-4 from this tick's inputs (core/xy/board/led.hpp).
  Led led() const { return led_pattern(battery_low_, in_.charger, ble_state(in_.ble_status1, in_.ble_status2)); }
  bool sleeping() const { return sleeping_; }
  // An off request is being served: the axes brake, then the counters are saved and the
  // KillSwitch is pulled; after that the core does nothing more (powered_off()).
  bool off_requested() const { return off_requested_; }
  bool powered_off() const { return powered_off_; }
  bool charging_allowed() const { return charging_; }
  bool session_open() const { return session_open_; }
  bool link_alive() const { return xy_axis::link_alive(watchdog_); }
  const xy_axis::State& axis_state(Axis a) const { return axes_[idx(a)]; }
  const xy_axis::Config& axis_config(Axis a) const { return derived_.cfg[idx(a)]; }
  const xy_axis::Mechanics& mechanics() const { return derived_.mech; }
  AxisEvent axis_event(Axis a) const { return event_[idx(a)]; }
  const MotorOutput& motor_output(Axis a) const { return motor_[idx(a)]; }
  // The axis core's output of this tick beyond the motor pins: the Tab. 7-3 edge it took and
  // its typed error (None when the tick's command, if any, was taken), for traces.
  xy_axis::Edge axis_edge(Axis a) const { return edge_[idx(a)]; }
  xy_axis::Error axis_error(Axis a) const { return error_[idx(a)]; }
  const Inputs& inputs() const { return in_; }
  const xy_storage::ParameterStore& store() const { return store_; }
  // The last good temperature (kNoTemperatureMc before the first), the integrated platform
  // rotation since power-up in [0, 359999] m°, and the sensors' state (docs/sensors.md).
  std::int32_t temperature_mc() const { return temperature_mc_; }
  std::int32_t rotation_mdeg() const { return rotation_.mdeg(); }
  const SensorStatus& sensors() const { return sensors_; }
  std::int32_t fault_code() const { return fault_; }
  BoardCounters counters() const;
  std::uint32_t ticks() const { return ticks_; }
  // The seq of the last frame taken (docs/protocol.md "Delivery"); none since power-up until
  // the first one.
  std::uint16_t last_seq() const { return last_seq_; }
  // Bytes received but not yet framed, and bytes of a frame the framer holds so far.
  std::size_t rx_pending() const { return rx_count_; }
  std::size_t framer_pending() const { return framer_.pending(); }
  xy_frame::AxisEcho axis_echo(Axis a) const;
  std::int32_t position_um(Axis a) const;
  // The coordinated path (docs/cnc.md "On the board").
  const xy_path::Executor& path() const { return path_; }
  // The last path segment's refusal this tick (xy_path::Error::None if none), for tests and traces.
  xy_path::Error path_error() const { return path_error_; }

 private:
  static constexpr std::size_t idx(Axis a) { return static_cast<std::size_t>(a); }
  static constexpr std::uint8_t kNoRefusal = 0xFF;

  struct PendingEcho {
    bool rejected = false;
    xy_frame::Rejection rejection{};
    std::uint16_t seq = 0;
    xy_frame::SubscriberSlots subs{};
    bool replay = false;  // answers a repeated or older frame: tells the outcome of the last one taken
  };
  // What the last frame taken did (docs/protocol.md "Delivery"): a repeat of it is answered
  // with the same refusals and block, so a client whose first echo was lost learns the same.
  struct Outcome {
    Block block = Block::None;
    std::array<std::uint8_t, kAxes> refused{kNoRefusal, kNoRefusal};
  };

  void begin_of_cycle();
  void receive();
  void handle(const xy_frame::RawCommandFramer::Event& e);
  void step_axes();
  void check_drivers();
  void configure_temperature();
  void configure_gyro();
  void read_sensors();
  void read_temperature();
  void read_gyro();
  void send_echoes();

  bool motion_permitted();
  enum class Pending : std::uint8_t { None, Accepted, Refused };
  Pending pending_motion(std::size_t i) const;
  xy_frame::HandlerStatus set_axis_command(Axis a, xy_codec::CommandId id, const xy_axis::Command& c);
  xy_frame::HandlerStatus set_parameter(Axis a, xy_codec::CommandId id, xy_storage::ParamId pid, std::int32_t value);
  bool apply_currents();
  bool apply_microsteps();
  void driver_fault(std::size_t i, xy_tmc2130::Error e);
  void request_off();
  void finish_shutdown();
  std::int64_t encoder_counts_at(std::int32_t pos) const;
  xy_frame::HandlerStatus refuse(Axis a, xy_codec::CommandId id);
  xy_frame::AxisEcho echo_of(std::size_t i, Block block, std::uint8_t refused) const;
  std::int32_t subscriber(xy_frame::SubscriberSlot slot);

  static xy_frame::HandlerStatus on_nop(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_stop(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_jog(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_goto(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_move(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_goto_slow(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_move_slow(void*, Axis, std::int32_t);
  // The axis core's speed levels (core/xy/axis Command::level).
  static constexpr std::uint8_t kLevelSlow = 0;
  static constexpr std::uint8_t kLevelFast = 1;
  xy_frame::HandlerStatus position_absolute(Axis a, xy_codec::CommandId id, std::int32_t um, std::uint8_t level);
  xy_frame::HandlerStatus position_relative(Axis a, xy_codec::CommandId id, std::int32_t um, std::uint8_t level);
  static xy_frame::HandlerStatus on_home(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_param(void*, Axis, std::int32_t, xy_codec::CommandId);
  template <xy_codec::CommandId Id>
  static xy_frame::HandlerStatus on_param_id(void* c, Axis a, std::int32_t d) {
    return on_param(c, a, d, Id);
  }
  static xy_frame::HandlerStatus on_periph_off(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_periph_on(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_save(void*, Axis, std::int32_t);
  static xy_frame::HandlerStatus on_clear(void*, Axis, std::int32_t);
  // Path parts are collected per frame and become one segment after the frame's dispatch
  // (path_commands.cpp): the X and Y parts of one frame are one XY segment.
  template <xy_codec::CommandId Id>
  static xy_frame::HandlerStatus on_path_part(void* c, Axis a, std::int32_t d) {
    return static_cast<Board*>(c)->path_part(a, Id, d);
  }
  static xy_frame::HandlerStatus on_path_end(void*, Axis, std::int32_t);
  xy_frame::HandlerStatus path_part(Axis a, xy_codec::CommandId id, std::int32_t um);
  void commit_path_frame(const xy_frame::CommandFrame& f);
  xy_path::Limits path_limits() const;
  void step_path(bool alive);
  void stop_path_by_user();
  static xy_frame::AxisEcho echo_axis(void* ctx, Axis a);
  static xy_frame::AxisEcho echo_axis_replay(void* ctx, Axis a);
  static std::int32_t echo_subscriber(void* ctx, xy_frame::SubscriberSlot slot);

  Hardware hw_;
  xy_storage::ParameterStore store_;
  std::array<xy_tmc2130::Driver, kAxes> drivers_;
  xy_tmp117::Driver tmp117_;
  xy_icm20789::Driver gyro_;
  xy_icm20789::Rotation rotation_{};
  std::int16_t gyro_held_ = 0;  // the last good sample, integrated for a failed read
  std::int32_t temperature_mc_ = kNoTemperatureMc;
  SensorStatus sensors_{};
  xy_frame::CallbackTable table_{};
  // The link layer only (syntax, CRC): command IDs and data are checked by table_ (Klipper
  // style), so an ID outside the table reaches table_'s own bound check.
  xy_frame::RawCommandFramer framer_{};
  Derived derived_{};

  std::array<std::uint8_t, kRxCapacity> rx_{};
  std::size_t rx_head_ = 0;  // next byte to read
  std::size_t rx_count_ = 0;

  Inputs in_{};
  MainState main_state_ = MainState::UserControl;
  Block block_ = Block::None;
  bool battery_low_ = false;
  bool session_open_ = false;
  bool sleeping_ = false;
  // A press held through power-up is the one that switched the unit on: an off request needs
  // the line released first.
  bool button_was_ = true;
  bool off_requested_ = false;
  bool powered_off_ = false;
  bool charging_ = true;
  bool charging_told_ = false;  // the charger enable was driven at least once since boot
  bool param_cycle_ = false;
  std::int32_t fault_ = 0;
  xy_axis::LinkWatchdog watchdog_{};
  bool frame_this_cycle_ = false;

  std::array<xy_axis::State, kAxes> axes_{};
  std::array<xy_axis::Command, kAxes> pending_{};
  std::array<xy_codec::CommandId, kAxes> pending_id_{};
  std::array<std::uint8_t, kAxes> refused_{kNoRefusal, kNoRefusal};
  std::array<AxisEvent, kAxes> event_{};
  std::array<MotorOutput, kAxes> motor_{};
  std::array<xy_axis::Edge, kAxes> edge_{xy_axis::Edge::I, xy_axis::Edge::I};
  std::array<xy_axis::Error, kAxes> error_{};

  xy_path::Executor path_{};
  std::array<xy_codec::CommandId, kAxes> path_id_{xy_codec::CommandId::Nop, xy_codec::CommandId::Nop};  // Nop: no path part
  std::array<std::int32_t, kAxes> path_um_{};
  bool centre_set_ = false;
  std::array<std::int32_t, kAxes> centre_um_{};  // the next arc's absolute centre
  xy_path::Error path_error_ = xy_path::Error::None;
  AxisEvent path_stop_event_ = AxisEvent::None;  // why the path is stopping

  std::array<PendingEcho, kMaxEchoesPerCycle> echoes_{};
  std::size_t echo_count_ = 0;
  std::uint16_t last_seq_ = 0;
  bool have_seq_ = false;
  bool taken_this_cycle_ = false;
  Outcome last_outcome_{};
  std::uint32_t ticks_ = 0;
  BoardCounters counters_{};
};

}  // namespace ap::xy_board
