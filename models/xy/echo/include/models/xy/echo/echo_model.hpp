// The reference model of what the PC sees: one expected echo per frame event the board
// handles, predicted from the documents (docs/board.md "One cycle" and "Echo content",
// docs/protocol.md, docs/motion.md §4-§8, docs/storage.md, docs/cnc.md for the coordinated
// path, seed-000.md §3.6-§3.7, §4.7) and
// written without reading core/xy/board's logic. docs/echo-model.md has the decisions.
//
// What the model predicts by itself: the echo's seq, each axis status, the data of every
// non-position status (fault code, reason*100 + offset, refused command ID), and which of
// the subscriber packets carry what. What it takes as an observation, because it is motion
// physics and core/xy/axis is verified against models/xy/motion on its own (docs/motion.md §12,
// §14): each axis's phase (Stop/Accel/Const/Decel) and step counter after the tick. From
// those it checks the position data (within 1 um of the counter) and names the moving
// statuses, and it checks that motion starts only when the model accepted a motion command.
//
// Use, once per 1 ms control tick, in this order (the board's cycle order):
//   model.begin_tick(env);                 // the inputs the board sampled this tick
//   model.frame(ev); ...                   // each frame event the board handles this tick
//   auto expected = model.end_tick(motion);// after the axes stepped: one Expected per event
//   check(expected[i], echo_i)             // -> std::optional<Mismatch>
// LinkTwin (board_checker.hpp) turns the UART bytes into the frame events as the board's
// receive path does; BoardChecker (board_checker.hpp) wires all of it to a xy_board::Board.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "core/xy/frame/frames.hpp"
#include "core/xy/i2c/port.hpp"
#include "core/xy/storage/parameters.hpp"

namespace ap::model::xy_echo {

inline constexpr std::size_t kAxes = 2;

// The two I2C sensors as their device models stand during a tick (docs/sensors.md). The
// model predicts from these what the board reads, when, and what it reports: never from the
// board's own temperature or angle.
struct SensorDevice {
  // How every transaction to the part ends in this tick: Ok, AddressNack (absent), DataNack,
  // BusError (the bus), or NoPort (the board has no sensor bus).
  ap::xy_i2c::Status answers = ap::xy_i2c::Status::NoPort;
  bool identity_ok = true;  // TMP117: Device_ID's DID = 0x117; ICM-20789: WHO_AM_I = 0x03
};
struct Sensors {
  SensorDevice tmp117{};
  std::uint16_t temp_result = 0x8000;  // the TMP117's Temp_Result register now
  SensorDevice gyro{};
  std::int16_t gyro_z = 0;             // the GYRO_ZOUT a read gives now (±250 °/s scale)
};

// Board-visible inputs of one tick (what Hardware::sample delivered, and the sensors).
struct Env {
  bool usb = false;
  bool charger = false;
  std::uint16_t battery_mv = 4000;
  std::int32_t charge_ma = 0;
  Sensors sensors{};
  bool ble_status1 = false;  // (0, 1) = Data Session open (Tab. 7-2)
  bool ble_status2 = true;
  std::array<bool, kAxes> endstop_min{};
  std::array<bool, kAxes> endstop_max{};
  bool button = false;  // the button controller's off request line (thesis §7.9.5)
};

// The observed motion of one axis after the tick (the axis core's phase and step counter,
// and the STEP pulses of this tick with their DIR).
enum class Phase : std::uint8_t { Stop = 0, Accel = 1, Const = 2, Decel = 3 };
struct AxisMotion {
  Phase phase = Phase::Stop;
  std::int32_t pos = 0;    // usteps
  std::int32_t steps = 0;  // emitted this tick
  std::int8_t dir = 1;
};
// The coordinated path's progress after the tick (docs/cnc.md "On the board"; docs/echo-model.md
// "The coordinated path"). Physics, not a verdict: how far the executor got (which segments are
// finished, when a chain starts, when a controlled stop comes to rest) follows from the S-curve
// and the interpolation, verified by properties/xy/path, scurve and interp on their own.
//   active: the path holds a segment or is still moving or stopping (xy_path::Executor::active()).
//   queued: segments queued and not yet finished, 0..16 (xy_path::Executor::queued()).
struct PathMotion {
  bool active = false;
  std::uint32_t queued = 0;
  // A chain is under way: its S-curve clock runs (possibly still below one step per tick).
  // A stop brakes such a chain; only a path with no chain under way is dropped at once.
  bool chain_running = false;
};
struct Motion {
  std::array<AxisMotion, kAxes> axis{};
  PathMotion path{};
  AxisMotion& operator[](std::size_t a) { return axis[a]; }
  const AxisMotion& operator[](std::size_t a) const { return axis[a]; }
};

// One frame event of the receive path: the link layer's verdict (syntax, CRC; docs/protocol.md
// "Receiving") and, when intact, the frame with its IDs as received (00..99, not yet checked
// against the tables: that is the callback table's job, predicted by the model).
struct FrameEvent {
  xy_frame::Rejection link{};
  xy_frame::CommandFrame frame{};
};

// What the model knows at power-up.
struct Boot {
  std::array<bool, kAxes> homed{};  // a valid encoder reading (or saved counter) seeded the counter
  std::array<std::int32_t, kAxes> pos{};  // the step counters after boot (observed, usteps)
  // Endstops active when the board sampled its inputs at boot: latched (motion.md §4, G8).
  std::array<bool, kAxes> endstop_min{};
  std::array<bool, kAxes> endstop_max{};
  // The parameter set in FRAM that the boot loads (docs/storage.md: the newest valid copy), as
  // the caller knows it (e.g. read from the FRAM by a store of its own); nullopt: the
  // defaults. A set that does not convert is replaced by the defaults and reported as fault
  // 4000 (docs/board.md "Power-up").
  std::optional<xy_storage::ParameterSet> params;
  // The sensors when the board configures them at the end of its boot.
  Sensors sensors{};
};

struct ExpectedAxis {
  xy_codec::EchoStatus status = xy_codec::EchoStatus::Idle;
  std::int32_t data = 0;  // exact, unless `position` is set
  bool position = false;  // data is the position in um: within 1 um of pos_usteps below
  std::int32_t pos_usteps = 0;
};

struct ExpectedPacket {
  xy_frame::SubscriberSlot slot{};
  std::optional<std::int32_t> data;  // nullopt: the model does not predict this value
};

struct Expected {
  std::uint16_t seq = 0;
  std::array<ExpectedAxis, kAxes> axis{};
  std::array<ExpectedPacket, xy_codec::kSubscriberSlots> subs{};
  // The mechanics in force when the echo was built (for the um <-> ustep tolerance).
  std::int64_t usteps_per_rev = 3200;
  std::int64_t pitch_um = 2000;
  std::string why;  // the model's reasoning, for the mismatch text
};

// What became of one frame the board took (docs/protocol.md "Outcomes"): run, or answered
// BLOCKED_* without running; and per part the command the axis refused, if any.
struct FrameFate {
  xy_frame::CommandFrame frame{};
  bool blocked = false;
  std::array<std::optional<xy_codec::CommandId>, kAxes> refused{};
};

struct Mismatch {
  std::string text;
};

// Compares one echo with its prediction; nullopt when they agree.
std::optional<Mismatch> check(const Expected& want, const xy_frame::EchoFrame& got);

// The model's own view of an axis (readable in mismatch texts and tests).
enum class Activity : std::uint8_t { Idle, Jog, Position, Home, Braking };
enum class Ended : std::uint8_t { None, Reached, Stopped, Endstop, LinkLost, HomeFailed };

class EchoModel {
 public:
  explicit EchoModel(const Boot& boot);

  void begin_tick(const Env& env);
  void frame(const FrameEvent& ev);
  // The expected echoes of this tick's frame events, in order. Also checks the observed
  // motion against the model (see violations()).
  std::span<const Expected> end_tick(const Motion& motion);

  // Observed motion the model forbids (an axis that starts with no accepted motion command,
  // or moves while blocked once stopped). Cleared by take_violations().
  std::vector<std::string> take_violations();

  // Observers for tests.
  Ended ended(std::size_t a) const { return ax_[a].ended; }
  bool blocked() const { return block_ != xy_codec::EchoStatus::Idle; }
  // This tick so far: frame events answered, and whether a new frame was taken (the board
  // takes at most one per tick: docs/protocol.md "Two frames in one cycle").
  std::size_t answers_this_tick() const { return events_.size(); }
  bool took_frame_this_tick() const { return taken_this_tick_; }
  // What the model says became of the frame taken this tick (valid after end_tick): the
  // ground truth the outcome oracle compares the client's reports with.
  const std::optional<FrameFate>& fate_this_tick() const { return fate_; }
  bool sleeping() const { return sleeping_; }
  std::uint32_t ticks() const { return ticks_; }
  // The temperature and angle the model expects the board to report now (m°C before the
  // wire clamp, m° in [0, 359999]).
  std::int32_t temperature_mc() const { return temperature_mc_; }
  std::int32_t rotation_mdeg() const;

 private:
  struct Params {
    std::int32_t accel = 20000, fast = 10000, slow = 2000, start = 500, homing = 2000;
    std::int32_t homing_mode = 1;  // docs/storage.md: only 1 (min endstop) homes
    std::int32_t pitch = 2000, steps = 200, micro = 16, irun = 16, ihold = 8;
    std::array<std::int32_t, kAxes> soft_min{0, 0}, soft_max{200000, 200000}, home_offset{0, 0};
    std::int32_t low_battery = 3300;
  };
  struct Ax {
    Activity act = Activity::Idle;
    std::int8_t jog_dir = 0;
    std::int32_t target = 0;  // usteps (Position)
    Ended ended = Ended::None;
    bool homed = false;
    bool latch_min = false, latch_max = false;
    std::optional<xy_codec::CommandId> refused;
    bool stop_requested = false;
    bool link_ended = false;
    bool started_now = false;  // a motion command was accepted in this cycle
    bool stopped_move_now = false;  // a stop of this cycle ended a move (Position) toward target
    AxisMotion last{};
  };

  // The coordinated path as the PC sees it (docs/cnc.md "On the board").
  enum class PathStop : std::uint8_t { None, User, Link, Block };
  struct PathState {
    bool running = false;                  // a segment was accepted; the path not yet seen at rest
    std::array<std::int32_t, kAxes> end{};  // usteps: the end of the last accepted segment
    std::uint32_t queued = 0;               // observed at the end of the last tick
    std::uint32_t added = 0;                // segments accepted in this tick
    bool centre_set = false;
    std::array<std::int32_t, kAxes> centre_um{};  // the next arc's centre, absolute um
    PathStop stop = PathStop::None;         // why the running path is stopping
    bool moved = false;                     // an axis was seen moving since it was accepted
    bool chain_running = false;             // observed at the end of the last tick
  };
  static bool is_path_part(xy_codec::CommandId id);
  void path_frame(const xy_frame::CommandFrame& f);
  const char* path_verdict(const xy_frame::CommandFrame& f, std::array<std::int32_t, kAxes>& end) const;
  void path_request_stop(PathStop why);
  // halted_on_switch: per axis, it stands now after a tick in which it stepped or was not yet
  // braking, and its last direction points into an active or latched endstop (cnc.md "Stops":
  // the path halts when an axis is about to step into the switch; one whose controlled stop
  // made no step toward it came to rest by itself).
  void path_end_tick(const Motion& motion, const std::array<bool, kAxes>& halted_on_switch);
  void path_finish(Ended e);

  void dispatch(xy_frame::Axis a, xy_codec::CommandId id, std::int32_t d);
  void refuse(std::size_t a, xy_codec::CommandId id, const char* why);
  bool motion_allowed(std::size_t a, std::int8_t dir) const;
  void supersede(std::size_t a);
  bool any_moving(bool or_started_now) const;
  std::optional<xy_frame::Rejection> table_check(const xy_frame::CommandFrame& f) const;
  bool set_param(xy_codec::CommandId id, std::int32_t d, std::string& why);
  static bool converts(const Params& p, std::string& why);
  std::int64_t to_usteps(std::int64_t um) const;  // nearest, half away from zero
  std::int32_t limit_min(std::size_t a) const;    // inward (up)
  std::int32_t limit_max(std::size_t a) const;    // inward (down)
  Expected build(std::size_t event) const;

  // docs/sensors.md "What the board does on an I2C error".
  enum class SensorMode : std::uint8_t { Unwired, Ok, Lost, Foreign };
  void configure_temperature(const Sensors& s);
  void configure_gyro(const Sensors& s);
  void sensors_tick();
  SensorMode temp_mode_ = SensorMode::Unwired;
  SensorMode gyro_mode_ = SensorMode::Unwired;
  std::uint32_t temp_misses_ = 0;
  std::uint32_t gyro_misses_ = 0;
  std::int32_t temperature_mc_ = -256000;  // Temp_Result's reset value until the first reading
  std::int64_t gyro_sum_ = 0;              // every integrated raw sample, unwrapped
  std::int16_t gyro_held_ = 0;

  Params p_{};
  PathState path_{};
  Env env_{};
  std::array<Ax, kAxes> ax_{};
  // Each axis as the axis core knows it at the start of the tick: a command of this tick is
  // only applied when the axes step, so a later one in the same cycle replaces it unseen.
  std::array<Ax, kAxes> at_tick_start_{};
  xy_codec::EchoStatus block_ = xy_codec::EchoStatus::Idle;  // Idle = not blocked, else BLOCKED_*
  bool battery_low_ = false;
  bool session_ = false;
  bool sleeping_ = false;
  // docs/board.md "Button and shutdown": a rising edge of the off request (after a release:
  // the press that switched the unit on does not count) is a sleep at the start of the tick.
  bool button_was_ = true;
  bool off_requested_ = false;
  void sleep_all();
  std::int32_t fault_ = 0;
  std::uint32_t since_dispatch_ = 0xFFFFFFFFU;  // ticks; starts expired (docs/motion.md §7)
  std::uint16_t last_seq_ = 0;
  bool have_seq_ = false;       // no frame taken since power-up
  bool taken_this_tick_ = false;
  xy_codec::EchoStatus last_block_ = xy_codec::EchoStatus::Idle;           // of the last frame taken
  std::array<std::optional<xy_codec::CommandId>, kAxes> last_refused_{};  // "
  std::optional<FrameFate> fate_;  // of the frame taken this tick
  xy_frame::CommandFrame taken_frame_{};
  std::uint32_t ticks_ = 0;
  bool dispatched_this_tick_ = false;

  struct Pending {
    bool rejected = false;
    xy_frame::Rejection rejection{};
    bool blocked = false;
    bool replay = false;  // a repeat or an older frame: answered, not run
    xy_frame::CommandFrame frame{};
  };
  std::vector<Pending> events_;
  std::vector<Expected> out_;
  std::vector<std::string> violations_;
};

}  // namespace ap::model::xy_echo
