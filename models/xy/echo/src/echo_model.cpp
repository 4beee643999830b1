// The echo reference model. Every rule cites the document it comes from; none is taken from
// core/xy/board (docs/echo-model.md).
#include "models/xy/echo/echo_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "protocol/xy/codec/errors.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::model::xy_echo {
namespace {

using xy_codec::CommandId;
using xy_codec::EchoStatus;
using xy_codec::FrameError;

// docs/motion.md §2 and §10: core ranges in usteps.
constexpr std::int64_t kSpeedMax = 1'000'000;      // usteps/s
constexpr std::int64_t kAccelMax = 10'000'000;     // usteps/s^2
constexpr std::int64_t kPosMax = 1'000'000'000;    // usteps
// docs/motion.md §7: alive while fewer than 300 ticks passed since the last dispatched frame.
constexpr std::uint32_t kWatchdogTicks = 300;
// docs/board.md G23.
constexpr std::int32_t kBatteryHysteresisMv = 100;
constexpr std::int32_t kFaultBadParams = 4000;   // docs/board.md "Power-up": defaults used

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
constexpr std::int32_t kTempWireMin = -99999;      // docs/protocol.md, subscriber "temp"
constexpr std::int32_t kTempWireMax = 999999;

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

std::string status_name(EchoStatus s) {
  const auto* info = xy_codec::find_status(static_cast<std::uint32_t>(s));
  return info != nullptr ? std::string(info->key) : "status" + std::to_string(static_cast<int>(s));
}

std::int64_t div_round_nearest(std::int64_t num, std::int64_t den) {  // den > 0, half away from zero
  const std::int64_t q = (std::llabs(num) * 2 + den) / (2 * den);
  return num < 0 ? -q : q;
}
std::int64_t div_floor(std::int64_t num, std::int64_t den) {
  std::int64_t q = num / den;
  if ((num % den != 0) && (num < 0)) --q;
  return q;
}
std::int64_t div_ceil(std::int64_t num, std::int64_t den) { return -div_floor(-num, den); }

bool power_of_two(std::int32_t v) { return v > 0 && (v & (v - 1)) == 0; }

// docs/cnc.md "Refusals": a segment's |delta| <= 2^24 usteps, an arc's offsets <= 2^20 usteps;
// the queue holds 16 segments.
constexpr std::int64_t kPathMaxDelta = std::int64_t{1} << 24;
constexpr std::int64_t kPathMaxOffset = std::int64_t{1} << 20;
constexpr std::uint32_t kPathQueue = 16;
// docs/cnc.md "Refusals": one segment of more than 2^20 moves (the S-curve's range) is TooLong;
// a line makes max |delta| moves (one driving step per move, "Speeds"), an arc is judged by the
// bound docs/cnc.md states, not by counting it. A longer *chain* is split, never refused.
constexpr std::int64_t kPathMaxMoves = std::int64_t{1} << 20;
// docs/cnc.md "Speeds": the jerk is the thesis's J = 20 mm/s^3 (seed-003.md §5.3.1), converted
// with the mechanics; v_max, a_max and J must lie in xy_scurve::Limits' ranges (BadLimits):
// v 1 .. 100 000 moves/s, a >= 1, J 1 .. 1e9, J <= 1000 a, J <= 1e6 v.
constexpr std::int64_t kPathJerkUm = 20000;
constexpr std::int64_t kPathMaxVelocity = 100000;
constexpr std::int64_t kPathMaxJerk = 1000000000;

std::int64_t isqrt_floor(std::int64_t v) {  // v >= 0
  auto r = static_cast<std::int64_t>(std::sqrt(static_cast<double>(v)));
  while (r * r > v) --r;
  while ((r + 1) * (r + 1) <= v) ++r;
  return r;
}

// Whether an arc around the origin from angle a0 to a1 (radians, atan2) passes angle t
// (inclusive at both ends: an end lying exactly on an axis direction counts as passing it,
// docs/echo-model.md "The coordinated path"). ccw: counter-clockwise (y up); a full circle
// (a0 == a1, start == end) passes everything.
bool arc_passes(double a0, double a1, double t, bool ccw, bool full) {
  if (full) return true;
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  constexpr double kEps = 1e-12;
  const auto norm = [&](double v) {
    v = std::fmod(v, kTwoPi);
    return v < 0 ? v + kTwoPi : v;
  };
  double sweep = ccw ? norm(a1 - a0) : norm(a0 - a1);
  if (sweep <= kEps) sweep = kTwoPi;
  const double d = ccw ? norm(t - a0) : norm(a0 - t);
  return d <= sweep + kEps || d >= kTwoPi - kEps;
}

}  // namespace

EchoModel::EchoModel(const Boot& boot) {
  for (std::size_t a = 0; a < kAxes; ++a) {
    ax_[a].homed = boot.homed[a];
    ax_[a].last.pos = boot.pos[a];
    ax_[a].latch_min = boot.endstop_min[a];
    ax_[a].latch_max = boot.endstop_max[a];
  }
  if (boot.params) {
    const xy_storage::ParameterSet& f = *boot.params;
    Params n = p_;
    n.accel = static_cast<std::int32_t>(f.max_acceleration_um_s2);
    n.fast = static_cast<std::int32_t>(f.fast_speed_um_s);
    n.slow = static_cast<std::int32_t>(f.slow_speed_um_s);
    n.start = static_cast<std::int32_t>(f.start_speed_um_s);
    n.homing = static_cast<std::int32_t>(f.homing_speed_um_s);
    n.homing_mode = f.homing_mode;
    n.pitch = static_cast<std::int32_t>(f.lead_pitch_um);
    n.steps = f.steps_per_rev;
    n.micro = f.microsteps;
    n.irun = f.run_current_cs;
    n.ihold = f.hold_current_cs;
    n.soft_min = {f.soft_min_x_um, f.soft_min_y_um};
    n.soft_max = {f.soft_max_x_um, f.soft_max_y_um};
    n.home_offset = {f.home_offset_x_um, f.home_offset_y_um};
    n.low_battery = f.low_battery_mv;
    std::string why;
    if (converts(n, why)) {
      p_ = n;
    } else {
      fault_ = kFaultBadParams;
    }
  }
  // docs/board.md "Step counter and boot": the sensors are configured last.
  configure_temperature(boot.sensors);
  configure_gyro(boot.sensors);
}

// ---------------------------------------------------------------- the I2C sensors
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

// ---------------------------------------------------------------- begin of cycle (§7.5.1)
void EchoModel::begin_tick(const Env& env) {
  ++ticks_;
  env_ = env;
  // G23: blocked below the stored threshold, left at threshold + 100 mV.
  if (battery_low_) {
    if (env.battery_mv >= p_.low_battery + kBatteryHysteresisMv) battery_low_ = false;
  } else if (env.battery_mv < p_.low_battery) {
    battery_low_ = true;
  }
  for (auto& x : ax_) {
    x.refused.reset();
    x.started_now = false;
    x.stopped_move_now = false;
  }
  // Priority of causes in the echo: USB > charger > battery (docs/board.md G23).
  const EchoStatus was = block_;
  block_ = env.usb ? EchoStatus::BlockedUsb
           : env.charger ? EchoStatus::BlockedCharger
           : battery_low_ ? EchoStatus::BlockedBattery
                          : EchoStatus::Idle;
  if (was == EchoStatus::Idle && block_ != EchoStatus::Idle) {
    // G16 / motion.md §7: blocking drops every pending move; the axes brake to a stop. What
    // ended a motion before the block (a user stop, the watchdog ending a jog) is the "last
    // event" G16 clears on leaving BLOCKED, also when the axis still brakes then
    // (docs/echo-model.md "Decisions"). It is decided now, not when the braking ends: an
    // answer to a repeat during the block shows it (docs/protocol.md "What a repeat answers").
    for (auto& x : ax_) {
      // A move whose carriage comes to rest on its target in the tick the block starts reached
      // it, as with a stop in the tick of arrival (docs/echo-model.md "Decisions").
      if (x.act == Activity::Position) x.stopped_move_now = true;
      if (x.act != Activity::Idle) x.act = Activity::Braking;
      if (x.stop_requested) x.ended = Ended::Stopped;
      else if (x.link_ended) x.ended = Ended::LinkLost;
      x.stop_requested = false;
      x.link_ended = false;
    }
    // cnc.md "Stops": a block is a controlled stop of the path; like the axes' own motion,
    // what ended it is cleared on leaving BLOCKED (G16).
    if (path_.running) path_.stop = PathStop::Block;
  }
  if (was != EchoStatus::Idle && block_ == EchoStatus::Idle) {
    // G16: back to user control with both axes idle and the last event cleared.
    for (auto& x : ax_) x.ended = Ended::None;
  }
  // Tab. 7-2 / G15: only Data Session open (STATUS1 = 0, STATUS2 = 1) carries commands.
  session_ = !env.ble_status1 && env.ble_status2;
  // docs/board.md "Button and shutdown": the off request is served before the tick's frames.
  if (env.button && !button_was_ && !off_requested_) {
    off_requested_ = true;
    sleep_all();
  }
  button_was_ = env.button;
  at_tick_start_ = ax_;
  path_.added = 0;
  events_.clear();
  out_.clear();
  dispatched_this_tick_ = false;
  taken_this_tick_ = false;
  fate_.reset();
}

// G24: the axes get a ramped stop; motion commands are refused until wake.
void EchoModel::sleep_all() {
  sleeping_ = true;
  path_request_stop(PathStop::User);  // cnc.md "Stops": sleep is a controlled stop
  for (std::size_t b = 0; b < kAxes; ++b) {
    supersede(b);
    Ax& y = ax_[b];
    if (y.act != Activity::Idle) {
      y.act = Activity::Braking;
      y.stop_requested = true;
    }
  }
}

// ---------------------------------------------------------------- receive (§7.5.1 step 3)
std::optional<xy_frame::Rejection> EchoModel::table_check(const xy_frame::CommandFrame& f) const {
  // docs/protocol.md "Dispatch": per axis part in wire order: ID against the table, then the
  // data against that command's range; then the subscriber slots. Offsets: ID_X 4, Data_X 6,
  // ID_Y 12, Data_Y 14, slot k ID 20 + 4k, argument 22 + 4k (the frame layout table).
  const std::array<std::pair<const xy_frame::AxisCommand*, std::uint16_t>, 2> parts{{{&f.x, 4}, {&f.y, 12}}};
  for (const auto& [part, off] : parts) {
    const auto id = static_cast<std::uint32_t>(part->id);
    if (id >= xy_codec::kCommands.size()) return xy_frame::Rejection{FrameError::UnknownCommand, off};
    if (!xy_codec::kCommands[id].range.contains(part->data)) {
      return xy_frame::Rejection{FrameError::DataOutOfRange, static_cast<std::uint16_t>(off + 2)};
    }
  }
  for (std::size_t k = 0; k < f.subs.size(); ++k) {
    const auto id = static_cast<std::uint32_t>(f.subs[k].id);
    const auto off = static_cast<std::uint16_t>(20 + 4 * k);
    const auto* info = xy_codec::find_subscriber(id);
    if (info == nullptr) return xy_frame::Rejection{FrameError::UnknownSubscriber, off};
    if (!info->arg_range.contains(f.subs[k].arg)) {
      return xy_frame::Rejection{FrameError::ArgOutOfRange, static_cast<std::uint16_t>(off + 2)};
    }
  }
  return std::nullopt;
}

void EchoModel::frame(const FrameEvent& ev) {
  Pending p;
  // G15 (docs/board.md): frames in any state but Data Session open are dropped without an
  // echo, damaged ones included.
  if (!session_) return;
  if (!ev.link.ok()) {  // the link layer rejected it: answered, nothing else (protocol.md)
    p.rejected = true;
    p.rejection = ev.link;
    p.frame.seq = last_seq_;  // the last accepted seq at this event (protocol.md)
    events_.push_back(p);
    return;
  }
  if (const auto r = table_check(ev.frame)) {
    p.rejected = true;
    p.rejection = *r;
    p.frame.seq = last_seq_;
    events_.push_back(p);
    return;
  }
  p.frame = ev.frame;
  // protocol.md "Delivery": a seq 1..499 ahead of the last one taken (mod 1000) is new, the
  // same seq is a repeat, 500..999 ahead is older; the first frame after power-up is new.
  // Neither a repeat nor an older frame runs; both are answered with the seq of the last frame
  // taken and its outcome (refusals, block); a repeat feeds the watchdog unless blocked.
  const int ahead = (static_cast<int>(ev.frame.seq) - static_cast<int>(last_seq_) + 1000) % 1000;
  if (have_seq_ && (ahead == 0 || ahead >= 500)) {
    p.replay = true;
    p.frame.seq = last_seq_;
    if (ahead == 0 && block_ == EchoStatus::Idle) {
      since_dispatch_ = 0;
      dispatched_this_tick_ = true;
    }
    events_.push_back(p);
    return;
  }
  have_seq_ = true;
  last_seq_ = ev.frame.seq;
  taken_this_tick_ = true;
  taken_frame_ = ev.frame;
  if (block_ != EchoStatus::Idle) {  // §7.5.2: commands cannot act while blocked; answered
    p.blocked = true;
    events_.push_back(p);
    return;
  }
  // Dispatched: X handler then Y handler; the watchdog is refreshed (G15).
  dispatch(xy_frame::Axis::X, ev.frame.x.id, ev.frame.x.data);
  dispatch(xy_frame::Axis::Y, ev.frame.y.id, ev.frame.y.data);
  // docs/cnc.md "From G-code to the axes" 2: the path parts of one frame are one segment,
  // checked and queued once both parts are handled.
  path_frame(ev.frame);
  since_dispatch_ = 0;
  dispatched_this_tick_ = true;
  events_.push_back(p);
}

void EchoModel::refuse(std::size_t a, CommandId id, const char*) { ax_[a].refused = id; }

bool EchoModel::motion_allowed(std::size_t a, std::int8_t dir) const {
  // motion.md §4 (G8): refused toward an endstop whose input is active or whose latch is set.
  const Ax& x = ax_[a];
  if (dir > 0) return !(env_.endstop_max[a] || x.latch_max);
  if (dir < 0) return !(env_.endstop_min[a] || x.latch_min);
  return true;
}

void EchoModel::supersede(std::size_t a) {
  // docs/board.md "One cycle": the handlers only store the command; the axis core applies
  // the last one of the cycle when the axes step. A motion command accepted earlier in this
  // tick and replaced now never reached the axis: no motion started, none ended, homing did
  // not clear the known position (docs/echo-model.md "Decisions"). Its refusal, if any, stays.
  Ax& x = ax_[a];
  if (!x.started_now) return;
  const auto refused = x.refused;
  x = at_tick_start_[a];
  x.refused = refused;
}

bool EchoModel::any_moving(bool or_started_now) const {
  // At rest (docs/board.md "Parameters and units"): standing and holding no motion (a jog
  // held at its reversal stop or at a soft limit moves again on the next tick; a move is
  // planned with the speeds it started with), and no motion command accepted earlier in this
  // frame (its distance was converted with the mechanics in force then).
  for (std::size_t a = 0; a < kAxes; ++a) {
    const Ax& x = ax_[a];
    if (x.last.phase != Phase::Stop || at_tick_start_[a].act != Activity::Idle || (or_started_now && x.started_now)) {
      return true;
    }
  }
  return false;
}

std::int64_t EchoModel::to_usteps(std::int64_t um) const {
  return div_round_nearest(um * p_.steps * p_.micro, p_.pitch);
}
std::int32_t EchoModel::limit_min(std::size_t a) const {
  return static_cast<std::int32_t>(div_ceil(static_cast<std::int64_t>(p_.soft_min[a]) * p_.steps * p_.micro, p_.pitch));
}
std::int32_t EchoModel::limit_max(std::size_t a) const {
  return static_cast<std::int32_t>(div_floor(static_cast<std::int64_t>(p_.soft_max[a]) * p_.steps * p_.micro, p_.pitch));
}

bool EchoModel::converts(const Params& p, std::string& why) {
  // docs/board.md "Parameters and units": a set that does not convert into valid axis
  // configs is refused; docs/motion.md §2 and §10 give the ranges and the rounding.
  const std::int64_t num = static_cast<std::int64_t>(p.steps) * p.micro;
  const auto conv = [&](std::int64_t um) { return div_round_nearest(um * num, p.pitch); };
  const std::int64_t v_fast = conv(p.fast), v_slow = conv(p.slow);
  std::int64_t v_start = conv(p.start);
  if (v_start < 1) v_start = 1;  // board.md: a start speed of 0 um/s starts at 1 ustep/s
  const std::int64_t acc = conv(p.accel);
  if (v_fast > kSpeedMax || v_slow > kSpeedMax) return why = "speed above 1e6 usteps/s", false;
  if (!(v_start <= v_slow && v_slow <= v_fast)) {
    return why = "speeds out of order in usteps", false;
  }
  if (acc < 1 || acc > kAccelMax) return why = "acceleration outside [1, 1e7] usteps/s^2", false;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const std::int64_t lo = div_ceil(static_cast<std::int64_t>(p.soft_min[a]) * num, p.pitch);
    const std::int64_t hi = div_floor(static_cast<std::int64_t>(p.soft_max[a]) * num, p.pitch);
    if (lo < -kPosMax || hi > kPosMax || lo >= hi) return why = "travel range empty or outside 1e9 usteps", false;
    if (2 * (hi - lo) > kPosMax) return why = "homing travel above 1e9 usteps", false;
    const std::int64_t home = conv(p.home_offset[a]);
    if (home < -kPosMax || home > kPosMax) return why = "home position outside 1e9 usteps", false;
  }
  return true;
}

bool EchoModel::set_param(CommandId id, std::int32_t d, std::string& why) {
  // docs/board.md "Parameters and units": range and rule (storage map) -> cross rules
  // (start <= slow <= fast) -> conversion -> both axes at rest (every
  // parameter except the two currents) -> save -> apply.
  if (id == CommandId::SetIrun) return p_.irun = d, true;
  if (id == CommandId::SetIhold) return p_.ihold = d, true;
  // docs/cnc.md "Refusals": the path was converted and planned with the parameters in force.
  if (path_.running) return why = "a path is active", false;
  Params n = p_;
  switch (id) {
    case CommandId::SetAccel: n.accel = d; break;
    case CommandId::SetFastSpeed: n.fast = d; break;
    case CommandId::SetSlowSpeed: n.slow = d; break;
    case CommandId::SetStartSpeed: n.start = d; break;
    case CommandId::SetPitch:
      if (d < 100 || d > 100000) return why = "pitch outside the storage range 100..100000", false;
      n.pitch = d;
      break;
    case CommandId::SetSteps:
      if (d > 1000) return why = "steps/rev outside the storage range 1..1000", false;
      n.steps = d;
      break;
    case CommandId::SetMicrosteps:
      if (!power_of_two(d)) return why = "microsteps not a power of two", false;
      n.micro = d;
      break;
    default: return why = "not a parameter", false;
  }
  if (!(n.start <= n.slow && n.slow <= n.fast)) return why = "cross rule", false;
  if (!converts(n, why)) return false;
  const bool mechanics = id == CommandId::SetPitch || id == CommandId::SetSteps || id == CommandId::SetMicrosteps;
  if (any_moving(mechanics)) return why = "an axis moves", false;
  // board.md: pitch, steps/rev and microsteps rescale the step counters so the position in
  // um is kept (the model's copy of the counter follows; the next observation overwrites it).
  const std::int64_t old_num = static_cast<std::int64_t>(p_.steps) * p_.micro * n.pitch;
  const std::int64_t new_num = static_cast<std::int64_t>(n.steps) * n.micro * p_.pitch;
  if (old_num != new_num) {
    for (auto& x : ax_) {
      x.last.pos = static_cast<std::int32_t>(div_round_nearest(static_cast<std::int64_t>(x.last.pos) * new_num, old_num));
    }
  }
  p_ = n;
  return true;
}

void EchoModel::dispatch(xy_frame::Axis axis, CommandId id, std::int32_t d) {
  const auto a = static_cast<std::size_t>(axis);
  Ax& x = ax_[a];
  const auto start = [&](Activity act) {
    supersede(a);
    x.act = act;
    x.ended = Ended::None;
    x.stop_requested = false;
    x.link_ended = false;
    x.started_now = true;
  };
  switch (id) {
    case CommandId::Nop: return;
    case CommandId::Stop:
    stop:
      // motion.md §6: a ramped stop, always accepted. cnc.md "Stops": either axis's stop
      // stops the path (a controlled stop along it).
      path_request_stop(PathStop::User);
      supersede(a);
      if (x.act != Activity::Idle) {
        x.stopped_move_now = x.act == Activity::Position;
        x.act = Activity::Braking;
        x.stop_requested = true;
      }
      return;
    case CommandId::Jog: {
      // cnc.md "Refusals": `jog` is refused while a path is active, its release (data 0) too
      // (docs/echo-model.md "The coordinated path").
      if (path_.running) return refuse(a, id, "a path is active");
      if (d == 0) goto stop;  // G20: key released = ramped stop
      const std::int8_t dir = d > 0 ? 1 : -1;
      if (sleeping_) return refuse(a, id, "sleeping");  // board.md G24
      if (!motion_allowed(a, dir)) return refuse(a, id, "toward an endstop");
      start(Activity::Jog);
      x.jog_dir = dir;
      return;
    }
    case CommandId::Goto:
    case CommandId::GotoSlow:
    case CommandId::Move:
    case CommandId::MoveSlow: {
      if (sleeping_) return refuse(a, id, "sleeping");
      if (path_.running) return refuse(a, id, "a path is active");  // cnc.md "Refusals"
      if (!x.homed) return refuse(a, id, "position unknown");  // motion.md §6
      std::int64_t target = 0;
      if (id == CommandId::Goto || id == CommandId::GotoSlow) {
        // motion.md §7 and §10: outside the um limits is refused; the rounded target is
        // pulled back onto an inward-rounded limit.
        if (d < p_.soft_min[a] || d > p_.soft_max[a]) return refuse(a, id, "outside the soft limits");
        target = to_usteps(d);
        if (target < limit_min(a)) target = limit_min(a);
        if (target > limit_max(a)) target = limit_max(a);
      } else {
        // motion.md §6: PP = AP + delta, checked against the limits like an absolute target.
        target = static_cast<std::int64_t>(x.last.pos) + to_usteps(d);
        if (target < limit_min(a) || target > limit_max(a)) return refuse(a, id, "outside the soft limits");
      }
      const std::int8_t dir = target > x.last.pos ? 1 : target < x.last.pos ? -1 : 0;
      if (!motion_allowed(a, dir)) return refuse(a, id, "toward an endstop");
      start(Activity::Position);
      x.target = static_cast<std::int32_t>(target);
      return;
    }
    case CommandId::Home:
      if (sleeping_) return refuse(a, id, "sleeping");
      if (path_.running) return refuse(a, id, "a path is active");  // cnc.md "Refusals"
      if (p_.homing_mode != 1) return refuse(a, id, "homing mode not 1");  // docs/storage.md
      start(Activity::Home);
      if (x.last.phase == Phase::Stop && (env_.endstop_min[a] || x.latch_min)) {
        // motion.md §6: resting on the (active or latched) min switch is the reference point.
        x.act = Activity::Idle;
        x.homed = true;
        x.ended = Ended::Reached;
        return;
      }
      x.homed = false;  // motion.md §6: homing clears the known position
      return;
    case CommandId::SetFastSpeed:
    case CommandId::SetSlowSpeed:
    case CommandId::SetAccel:
    case CommandId::SetStartSpeed:
    case CommandId::SetPitch:
    case CommandId::SetSteps:
    case CommandId::SetMicrosteps:
    case CommandId::SetIrun:
    case CommandId::SetIhold: {
      std::string why;
      if (!set_param(id, d, why)) refuse(a, id, "parameter");
      return;
    }
    case CommandId::PeriphOff:
      sleep_all();
      return;
    case CommandId::PeriphOn: sleeping_ = false; return;
    case CommandId::SaveParams: return;
    case CommandId::ClearFault: fault_ = 0; return;
    case CommandId::PathLine:
    case CommandId::PathCentre:
    case CommandId::PathArcCw:
    case CommandId::PathArcCcw:
    case CommandId::PathEnd: return;  // path_frame(), once both parts are handled
  }
}

// ---------------------------------------------------------------- the coordinated path
// docs/cnc.md "From G-code to the axes" and "On the board"; the decisions where it is silent
// are in docs/echo-model.md "The coordinated path".
bool EchoModel::is_path_part(CommandId id) {
  return id == CommandId::PathLine || id == CommandId::PathCentre || id == CommandId::PathArcCw ||
         id == CommandId::PathArcCcw;
}

void EchoModel::path_request_stop(PathStop why) {
  if (!path_.running || path_.stop == PathStop::Block) return;
  // A user stop names the end even after the link expired (as for a jog: the user's stop is
  // what the PC asked for last); a block overrides both (G16 clears the event).
  if (why == PathStop::Link && path_.stop != PathStop::None) return;
  path_.stop = why;
  // A path standing (no chain moving: waiting to be closed, or between chains) has nothing to
  // brake: the stop drops its queue at once, so a command later in the same cycle finds no
  // path (docs/echo-model.md "The coordinated path").
  // Standing is observed, like every motion: no chain under way at the end of the last tick.
  // A chain whose S-curve has begun brakes along it even before its first step (found by the
  // board fuzz target: a stop two ticks after path_end, with coarse steps, no step yet).
  if (why == PathStop::User && !path_.chain_running && ax_[0].last.phase == Phase::Stop &&
      ax_[1].last.phase == Phase::Stop) {
    path_finish(path_.moved ? Ended::Stopped : Ended::None);
  }
}

void EchoModel::path_finish(Ended e) {
  // The event that ended the last motion; a path that never moved ended none (like a stop at
  // rest, docs/echo-model.md "Decisions"), the axes keep IDLE.
  if (block_ != EchoStatus::Idle || !path_.moved) e = Ended::None;
  for (Ax& x : ax_) x.ended = e;
  path_.running = false;
  path_.moved = false;
  path_.stop = PathStop::None;
}

const char* EchoModel::path_verdict(const xy_frame::CommandFrame& f, std::array<std::int32_t, kAxes>& end) const {
  const std::array<const xy_frame::AxisCommand*, kAxes> part{&f.x, &f.y};
  bool line = false, cw = false, ccw = false, centre = false;
  for (const auto* q : part) {
    line |= q->id == CommandId::PathLine;
    cw |= q->id == CommandId::PathArcCw;
    ccw |= q->id == CommandId::PathArcCcw;
    centre |= q->id == CommandId::PathCentre;
  }
  const int kinds = int{line} + int{cw} + int{ccw};
  if (kinds > 1 || (centre && kinds > 0)) return "mixed parts";  // MixedParts
  // cnc.md "Refusals": a centre frame without both parts is MixedParts too.
  if (centre && (f.x.id != CommandId::PathCentre || f.y.id != CommandId::PathCentre)) return "centre without both parts";
  if (centre) return nullptr;  // a centre is only stored (decision, docs/echo-model.md)
  // cnc.md "Refusals": a segment beside a motion command or a stop is MixedParts.
  for (const auto* q : part) {
    if (q->id == CommandId::Stop || q->id == CommandId::Jog || q->id == CommandId::Goto || q->id == CommandId::Move ||
        q->id == CommandId::GotoSlow || q->id == CommandId::MoveSlow || q->id == CommandId::Home) {
      return "a segment beside a motion command";
    }
  }
  // A motion command accepted earlier in this cycle is only stored: the segment supersedes it
  // (docs/board.md "One cycle"; supersede()), so the axes count as the axis core knows them.
  const auto known = [&](std::size_t a) -> const Ax& { return ax_[a].started_now ? at_tick_start_[a] : ax_[a]; };
  if (!known(0).homed || !known(1).homed) return "not homed";
  if (sleeping_) return "sleeping";
  for (std::size_t a = 0; a < kAxes; ++a) {
    // Busy: moving on its own, or a motion command accepted earlier in this tick (docs/cnc.md).
    if (ax_[a].started_now || known(a).act != Activity::Idle) return "an axis moves on its own";
  }
  if (path_.running && path_.stop != PathStop::None) return "a stop is running";  // Stopping
  if ((cw || ccw) && !path_.centre_set) return "arc without a centre";             // NoCentre
  // The segment starts where the queue ends, or at the axes' position when nothing is queued.
  const std::array<std::int64_t, kAxes> start{path_.running ? path_.end[0] : ax_[0].last.pos,
                                              path_.running ? path_.end[1] : ax_[1].last.pos};
  std::array<std::int64_t, kAxes> e{};
  for (std::size_t a = 0; a < kAxes; ++a) {
    // cnc.md step 3: um -> usteps nearest, as goto; a part carrying something else keeps the
    // axis where the queue ends.
    e[a] = (part[a]->id == CommandId::PathLine || part[a]->id == CommandId::PathArcCw ||
            part[a]->id == CommandId::PathArcCcw)
               ? to_usteps(part[a]->data)
               : start[a];
    if (e[a] < limit_min(a) || e[a] > limit_max(a)) return "end outside the soft limits";
    if (std::llabs(e[a] - start[a]) > kPathMaxDelta) return "too long";
  }
  if (line) {
    if (e == start) return "zero length";
    if (std::max(std::llabs(e[0] - start[0]), std::llabs(e[1] - start[1])) > kPathMaxMoves) return "too long";
  } else {
    std::array<std::int64_t, kAxes> c{};
    for (std::size_t a = 0; a < kAxes; ++a) {
      // cnc.md step 2: the centre's absolute position in um, converted like an end.
      c[a] = to_usteps(path_.centre_um[a]);
      if (std::llabs(c[a] - start[a]) > kPathMaxOffset) return "too long";
    }
    if (c == start || c == e) return "zero radius";
    const auto sq = [](std::int64_t v) { return v * v; };
    const std::int64_t rs = isqrt_floor(sq(start[0] - c[0]) + sq(start[1] - c[1]));
    const std::int64_t re = isqrt_floor(sq(e[0] - c[0]) + sq(e[1] - c[1]));
    // max(2 steps, 0.1 % of r): for integers |rs - re| > r/1000 exactly when > floor(r/1000).
    const std::int64_t tol = rs / 1000 > 2 ? rs / 1000 : 2;
    if (std::llabs(rs - re) > tol) return "radius mismatch";
    // docs/cnc.md "Refusals": an arc's moves are bounded by (r + 2) * 5794 / 1024 + 2 |rs - re| + 32.
    if ((rs + 2) * 5794 / 1024 + 2 * std::llabs(rs - re) + 32 > kPathMaxMoves) return "too long";
    // Swept extremes along each axis direction the arc passes (in double): c +- k with k the
    // largest integer with k - 1/2 < r, r the exact start radius in steps (cnc.md "Refusals":
    // every raster point is within 1/2 step of the circle).
    const double a0 = std::atan2(static_cast<double>(start[1] - c[1]), static_cast<double>(start[0] - c[0]));
    const double a1 = std::atan2(static_cast<double>(e[1] - c[1]), static_cast<double>(e[0] - c[0]));
    const bool full = e == start;
    const double r_exact = std::sqrt(static_cast<double>(sq(start[0] - c[0]) + sq(start[1] - c[1])));
    const double reach = std::ceil(r_exact + 0.5) - 1.0;
    constexpr double kHalfPi = 1.57079632679489661923;
    for (int k = 0; k < 4; ++k) {
      if (!arc_passes(a0, a1, k * kHalfPi, ccw, full)) continue;
      const std::size_t a = (k % 2 == 0) ? 0 : 1;  // 0, 180 deg: x; 90, 270 deg: y
      const double extreme = static_cast<double>(c[a]) + (k < 2 ? reach : -reach);
      if (extreme > static_cast<double>(limit_max(a)) || extreme < static_cast<double>(limit_min(a))) {
        return "swept extreme outside the soft limits";
      }
    }
  }
  {
    // cnc.md "Speeds": the path's v_max is the axes' fast speed, at most 100 000 moves/s.
    const std::int64_t v = std::min<std::int64_t>(to_usteps(p_.fast), kPathMaxVelocity);
    const std::int64_t acc = to_usteps(p_.accel), j = to_usteps(kPathJerkUm);
    if (v < 1 || v > kPathMaxVelocity || acc < 1 || j < 1 || j > kPathMaxJerk || j > 1000 * acc || j > 1000000 * v) {
      return "speed, acceleration or jerk outside scurve's ranges";  // BadLimits
    }
  }
  if (path_.queued + path_.added >= kPathQueue) return "queue full";
  for (std::size_t a = 0; a < kAxes; ++a) end[a] = static_cast<std::int32_t>(e[a]);
  return nullptr;
}

void EchoModel::path_frame(const xy_frame::CommandFrame& f) {
  const std::array<const xy_frame::AxisCommand*, kAxes> part{&f.x, &f.y};
  if (!is_path_part(f.x.id) && !is_path_part(f.y.id)) return;
  std::array<std::int32_t, kAxes> end{};
  if (path_verdict(f, end) != nullptr) {
    // cnc.md "Refusals": the echo's COMMAND_REFUSED with the command's ID on each part that
    // carried a path command; nothing changes.
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (is_path_part(part[a]->id)) ax_[a].refused = part[a]->id;
    }
    return;
  }
  if (f.x.id == CommandId::PathCentre) {  // both parts carry it (path_verdict)
    path_.centre_set = true;
    for (std::size_t a = 0; a < kAxes; ++a) path_.centre_um[a] = part[a]->data;
    return;
  }
  if (f.x.id != CommandId::PathLine && f.y.id != CommandId::PathLine) path_.centre_set = false;  // used by its arc
  for (std::size_t a = 0; a < kAxes; ++a) supersede(a);  // the path drives both axes now
  path_.running = true;
  path_.end = end;
  ++path_.added;
  // A motion starts: the event that ended the last one no longer describes the axes.
  for (Ax& x : ax_) x.ended = Ended::None;
}

void EchoModel::path_end_tick(const Motion& motion) {
  path_.queued = motion.path.queued;
  path_.chain_running = motion.path.chain_running;
  if (motion.path.active && !path_.running) {
    violations_.push_back("the path is active at tick " + std::to_string(ticks_) + " with no accepted segment");
  }
  if (path_.running && (motion[0].phase != Phase::Stop || motion[1].phase != Phase::Stop || motion[0].steps > 0 ||
                        motion[1].steps > 0)) {
    path_.moved = true;
  }
  if (!path_.running || motion.path.active) return;
  // The path came to rest (cnc.md "Stops"): a stop names its cause; otherwise at the end of
  // the last segment it reached it, and short of it an endstop halted it.
  Ended e = Ended::None;
  const bool at_end = motion[0].pos == path_.end[0] && motion[1].pos == path_.end[1];
  switch (path_.stop) {
    case PathStop::Block: e = Ended::None; break;
    case PathStop::User: e = Ended::Stopped; break;
    case PathStop::Link: e = Ended::LinkLost; break;
    case PathStop::None: e = at_end ? Ended::Reached : Ended::Endstop; break;
  }
  path_finish(e);
}

// ---------------------------------------------------------------- after the axes stepped
std::span<const Expected> EchoModel::end_tick(const Motion& motion) {
  // G15: a jog needs a dispatched frame within the last 300 ticks and an open session.
  const bool alive = session_ && since_dispatch_ < kWatchdogTicks;
  if (since_dispatch_ < 0xFFFFFFFFU) ++since_dispatch_;
  // cnc.md "Stops": a lost link or a closed session stops the path (unlike a move).
  if (!alive) path_request_stop(PathStop::Link);
  for (std::size_t a = 0; a < kAxes; ++a) {
    Ax& x = ax_[a];
    const AxisMotion& m = motion[a];
    const AxisMotion prev = x.last;
    const bool moving = m.phase != Phase::Stop;
    const bool was_moving = prev.phase != Phase::Stop;
    if (x.act == Activity::Jog && !alive) {
      x.act = Activity::Braking;
      x.stop_requested = false;  // the link ended it, not the user
      x.ended = Ended::None;
      x.jog_dir = 0;
      x.link_ended = true;
    }
    // Endstop latches (motion.md §4): set while the input is active, cleared by a step away
    // with the input released.
    if (env_.endstop_min[a]) x.latch_min = true;
    else if (x.latch_min && m.steps > 0 && m.dir > 0) x.latch_min = false;
    if (env_.endstop_max[a]) x.latch_max = true;
    else if (x.latch_max && m.steps > 0 && m.dir < 0) x.latch_max = false;

    const bool at_min = env_.endstop_min[a], at_max = env_.endstop_max[a];
    const bool endstop_in_dir = (prev.dir < 0 && at_min) || (prev.dir > 0 && at_max);

    if (block_ != EchoStatus::Idle) {
      if (moving && !was_moving) violations_.push_back("axis " + std::string(a == 0 ? "x" : "y") + " started while blocked");
      // The event that ended the last motion stands until G16 clears it at the block's end;
      // the answer to a repeat shows it meanwhile (docs/protocol.md "What a repeat answers").
      // The braking under the block may end on a switch, or, in the block's first tick, on the
      // move's own target (block entry above).
      if (!moving && x.act != Activity::Idle) {
        if (was_moving && endstop_in_dir) x.ended = Ended::Endstop;
        else if (x.stopped_move_now && m.pos == x.target) x.ended = Ended::Reached;
        x.act = Activity::Idle;
      }
      x.last = m;
      continue;
    }
    if (moving) {
      if (x.act == Activity::Idle && !was_moving && !path_.running) {
        violations_.push_back("axis " + std::string(a == 0 ? "x" : "y") + " started at tick " + std::to_string(ticks_) +
                              " with no accepted motion command");
      }
      x.last = m;
      continue;
    }
    // Standing after this tick.
    switch (x.act) {
      case Activity::Idle: break;
      case Activity::Jog:
        if (was_moving && endstop_in_dir) {  // G/H: an endstop ends the jog
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        }
        // Otherwise a reversal (E then A next tick) or the jog braked onto its soft limit:
        // the jog is still held.
        break;
      case Activity::Position:
        if (m.pos == x.target) {
          x.act = Activity::Idle;
          x.ended = Ended::Reached;
        } else if (was_moving && endstop_in_dir) {
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        } else if (!was_moving && !motion_allowed(a, m.pos < x.target ? 1 : -1)) {
          // Standing short of the target (the reversal stop of a move that turned round) with
          // the switch toward the target active or latched: motion.md §4 refuses motion toward
          // it, so the endstop ended the move (docs/echo-model.md "Decisions").
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        }
        break;
      case Activity::Home:
        if (was_moving && prev.dir > 0 && at_max) {  // braking upward into the max switch: H
          x.act = Activity::Idle;
          x.ended = Ended::Endstop;
        } else if (was_moving && prev.dir > 0) {
          // The reversal stop of a Home issued while moving up: still homing. motion.md §6
          // takes the reference "at standstill", i.e. from the next tick on, also when the
          // min switch is already active (docs/echo-model.md "Decisions").
        } else if (at_min || (!was_moving && x.latch_min)) {
          // G19: the min endstop is the reference point; at standstill a latched switch counts
          // as active (motion.md §4).
          x.act = Activity::Idle;
          x.homed = true;
          x.ended = Ended::Reached;  // the reference position is reached (decision)
        } else if (was_moving && prev.dir < 0) {  // travelled toward min without a switch
          x.act = Activity::Idle;
          x.ended = Ended::HomeFailed;
        }
        break;
      case Activity::Braking:
        x.act = Activity::Idle;
        if (was_moving && endstop_in_dir) x.ended = Ended::Endstop;
        // A stop given in the very tick a move comes to rest on its target ended nothing the
        // move did not end itself: REACHED (docs/echo-model.md "Decisions").
        else if (x.stopped_move_now && m.pos == x.target) x.ended = Ended::Reached;
        else if (x.stop_requested) x.ended = Ended::Stopped;
        else if (x.link_ended) x.ended = Ended::LinkLost;
        x.stop_requested = false;
        x.link_ended = false;
        break;
    }
    x.last = m;
  }
  path_end_tick(motion);
  sensors_tick();
  if (taken_this_tick_) {
    last_block_ = block_;
    for (std::size_t a = 0; a < kAxes; ++a) last_refused_[a] = ax_[a].refused;
    fate_ = FrameFate{taken_frame_, block_ != EchoStatus::Idle, last_refused_};
  }
  for (std::size_t i = 0; i < events_.size(); ++i) out_.push_back(build(i));
  return out_;
}

Expected EchoModel::build(std::size_t i) const {
  const Pending& ev = events_[i];
  Expected e;
  e.usteps_per_rev = static_cast<std::int64_t>(p_.steps) * p_.micro;
  e.pitch_um = p_.pitch;
  if (ev.rejected) {
    // protocol.md "What a rejected frame may change": both axes FRAME_REJECTED with
    // reason*100 + offset, seq = last accepted seq, empty subscriber packets.
    e.seq = ev.frame.seq;
    const std::int32_t data = static_cast<std::int32_t>(ev.rejection.error) * xy_codec::kRejectReasonScale + ev.rejection.offset;
    for (auto& x : e.axis) x = {EchoStatus::FrameRejected, data, false, 0};
    for (auto& s : e.subs) s = {xy_frame::SubscriberSlot{}, 0};
    e.why = "frame rejected (" + std::to_string(static_cast<int>(ev.rejection.error)) + " at " +
            std::to_string(ev.rejection.offset) + ")";
    return e;
  }
  e.seq = ev.frame.seq;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const Ax& x = ax_[a];
    ExpectedAxis& o = e.axis[a];
    o.position = true;
    o.pos_usteps = x.last.pos;
    // board.md "Echo content": BLOCKED_* > COMMAND_REFUSED > FAULT > SLEEPING > moving
    // (HOMING / ACCEL / CONST / DECEL) > the event that ended the last motion > IDLE.
    // An answer to a repeat or an older frame tells the block and refusals the last frame
    // taken had when it was taken (protocol.md "Delivery"), not a block of today: the client
    // reads BLOCKED_* as "did not take effect". The state is today's.
    const EchoStatus block = ev.replay ? last_block_ : block_;
    const std::optional<CommandId> refused = ev.replay ? last_refused_[a] : x.refused;
    if (block != EchoStatus::Idle) {
      o.status = block;
    } else if (refused) {
      o = {EchoStatus::CommandRefused, static_cast<std::int32_t>(*refused), false, 0};
    } else if (fault_ != 0) {
      o = {EchoStatus::Fault, fault_, false, 0};
    } else if (sleeping_) {
      o.status = EchoStatus::Sleeping;
    } else if (x.last.phase != Phase::Stop) {
      o.status = x.act == Activity::Home ? EchoStatus::Homing
                 : x.last.phase == Phase::Accel ? EchoStatus::Accelerating
                 : x.last.phase == Phase::Const ? EchoStatus::ConstantSpeed
                                                : EchoStatus::Decelerating;
    } else {
      switch (x.ended) {
        case Ended::Reached: o.status = EchoStatus::TargetReached; break;
        case Ended::Stopped: o.status = EchoStatus::StoppedByUser; break;
        case Ended::Endstop: o.status = EchoStatus::EndstopHit; break;
        case Ended::LinkLost: o.status = EchoStatus::LinkLost; break;
        case Ended::HomeFailed: o.status = EchoStatus::Idle; break;
        case Ended::None: o.status = EchoStatus::Idle; break;
      }
    }
  }
  for (std::size_t k = 0; k < e.subs.size(); ++k) {
    const xy_frame::SubscriberSlot s = ev.frame.subs[k];
    ExpectedPacket& o = e.subs[k];
    o.slot = s;
    switch (s.id) {
      case xy_codec::SubscriberId::None: o.data = 0; break;
      case xy_codec::SubscriberId::BatteryMv: o.data = env_.battery_mv; break;
      case xy_codec::SubscriberId::ChargeMa: o.data = env_.charge_ma; break;
      case xy_codec::SubscriberId::TemperatureMc:
        o.data = std::clamp(temperature_mc_, kTempWireMin, kTempWireMax);  // docs/sensors.md "Wire range"
        break;
      case xy_codec::SubscriberId::RotationMdeg: o.data = rotation_mdeg(); break;
      case xy_codec::SubscriberId::Param:
        switch (s.arg) {  // docs/storage.md map ids
          case 0: o.data = p_.accel; break;
          case 1: o.data = p_.fast; break;
          case 2: o.data = p_.slow; break;
          case 3: o.data = p_.start; break;
          case 4: o.data = p_.pitch; break;
          case 5: o.data = p_.steps; break;
          case 6: o.data = p_.micro; break;
          case 7: o.data = p_.irun; break;
          case 8: o.data = p_.ihold; break;
          case 15: o.data = p_.homing; break;
          case 19: o.data = p_.low_battery; break;
          default: o.data.reset(); break;
        }
        break;
      default: o.data.reset(); break;  // encoder, DRV_STATUS, link counters: not modelled
    }
  }
  e.why = block_ != EchoStatus::Idle ? "blocked" : "dispatched";
  return e;
}

std::vector<std::string> EchoModel::take_violations() {
  std::vector<std::string> v;
  v.swap(violations_);
  return v;
}

// ---------------------------------------------------------------- comparison
std::optional<Mismatch> check(const Expected& want, const xy_frame::EchoFrame& got) {
  std::string t;
  const auto add = [&](const std::string& s) { t += (t.empty() ? "" : "; ") + s; };
  if (got.seq != want.seq) add("seq " + std::to_string(got.seq) + ", model expects " + std::to_string(want.seq));
  for (std::size_t a = 0; a < kAxes; ++a) {
    const ExpectedAxis& w = want.axis[a];
    const xy_frame::AxisEcho& g = a == 0 ? got.x : got.y;
    const std::string an = a == 0 ? "x" : "y";
    if (g.status != w.status) {
      add(an + " status " + status_name(g.status) + " (data " + std::to_string(g.data) + "), model expects " +
          status_name(w.status));
      continue;
    }
    if (w.position) {
      // Within 1 um of the step counter: |data * usteps_per_rev - pos * pitch| <= usteps_per_rev.
      // docs/protocol.md status table: the position field carries -99999 .. 999999 um; a
      // position beyond it is sent as the nearest end (the counter itself goes to +-1e9 usteps).
      const std::int64_t um_x_rev = static_cast<std::int64_t>(w.pos_usteps) * want.pitch_um;
      const std::int64_t diff = static_cast<std::int64_t>(g.data) * want.usteps_per_rev - um_x_rev;
      const bool beyond_min = g.data == xy_codec::kPositionRange.min && um_x_rev <= g.data * want.usteps_per_rev;
      const bool beyond_max = g.data == xy_codec::kPositionRange.max && um_x_rev >= g.data * want.usteps_per_rev;
      if (std::llabs(diff) > want.usteps_per_rev && !beyond_min && !beyond_max) {
        add(an + " position " + std::to_string(g.data) + " um, step counter " + std::to_string(w.pos_usteps) +
            " usteps is not within 1 um of it");
      }
    } else if (g.data != w.data) {
      add(an + " " + status_name(w.status) + " data " + std::to_string(g.data) + ", model expects " +
          std::to_string(w.data));
    }
  }
  for (std::size_t k = 0; k < want.subs.size(); ++k) {
    const ExpectedPacket& w = want.subs[k];
    const xy_frame::SubscriberPacket& g = got.subs[k];
    if (!(g.slot == w.slot)) {
      add("packet " + std::to_string(k) + " slot " + std::to_string(static_cast<int>(g.slot.id)) + "/" +
          std::to_string(g.slot.arg) + ", model expects " + std::to_string(static_cast<int>(w.slot.id)) + "/" +
          std::to_string(w.slot.arg));
    } else if (w.data && g.data != *w.data) {
      add("packet " + std::to_string(k) + " data " + std::to_string(g.data) + ", model expects " +
          std::to_string(*w.data));
    }
  }
  if (t.empty()) return std::nullopt;
  return Mismatch{"echo seq " + std::to_string(got.seq) + " (" + want.why + "): " + t};
}

}  // namespace ap::model::xy_echo
