#include "core/xy/board/board.hpp"
#include "core/xy/board/driver_setup.hpp"

#include <algorithm>
#include <limits>

#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "core/xy/frame/echo_builder.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/tmc2130/fields.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
namespace st = ap::xy_storage;
namespace tmc = ap::xy_tmc2130;
using xy_frame::HandlerStatus;

namespace {

constexpr std::int32_t clamp32(std::int64_t v) {
  return static_cast<std::int32_t>(std::clamp<std::int64_t>(v, std::numeric_limits<std::int32_t>::min(),
                                                             std::numeric_limits<std::int32_t>::max()));
}

constexpr std::int32_t wrap_million(std::uint32_t v) { return static_cast<std::int32_t>(v % 1'000'000U); }

bool moving(const xy_axis::State& s) { return s.phase != xy_axis::Phase::Stop; }

// docs/protocol.md, the subscriber table: -99999 .. 999999 m°C (the table is indexed by ID).
constexpr c::Range kTemperatureWire = c::kSubscribers[static_cast<std::size_t>(c::SubscriberId::TemperatureMc)].range;

}  // namespace

Derived derive(const st::ParameterSet& p) {
  Derived d;
  if (!st::validate(p).ok()) return d;
  d.mech = xy_axis::Mechanics{static_cast<std::int32_t>(p.lead_pitch_um), p.steps_per_rev, p.microsteps};
  if (!xy_axis::mechanics_valid(d.mech)) return d;
  const auto start = xy_axis::speed_to_usteps(static_cast<std::int32_t>(p.start_speed_um_s), d.mech);
  const auto slow = xy_axis::speed_to_usteps(static_cast<std::int32_t>(p.slow_speed_um_s), d.mech);
  const auto fast = xy_axis::speed_to_usteps(static_cast<std::int32_t>(p.fast_speed_um_s), d.mech);
  const auto accel = xy_axis::accel_to_usteps(static_cast<std::int32_t>(p.max_acceleration_um_s2), d.mech);
  if (start.error != xy_axis::Error::None || slow.error != xy_axis::Error::None || fast.error != xy_axis::Error::None ||
      accel.error != xy_axis::Error::None) {
    return d;
  }
  const std::array<std::array<std::int32_t, 3>, kAxes> per_axis{{
      {p.soft_min_x_um, p.soft_max_x_um, p.home_offset_x_um},
      {p.soft_min_y_um, p.soft_max_y_um, p.home_offset_y_um},
  }};
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto lim = xy_axis::limits_to_usteps(per_axis[i][0], per_axis[i][1], d.mech);
    const auto home = xy_axis::um_to_usteps(per_axis[i][2], d.mech, xy_axis::Round::Nearest);
    if (lim.error != xy_axis::Error::None || home.error != xy_axis::Error::None) return d;
    xy_axis::Config& cfg = d.cfg[i];
    // A start speed of 0 µm/s (allowed by the map) or one that rounds to 0 means "start at
    // the lowest speed the step function knows", 1 ustep/s.
    cfg.v_start = std::max<std::int32_t>(start.value, 1);
    cfg.v_slow = slow.value;
    cfg.v_fast = fast.value;
    cfg.accel = accel.value;
    cfg.soft_min = lim.min;
    cfg.soft_max = lim.max;
    // Homing gives up after twice the travel range: from anywhere inside it the min endstop
    // must have been seen by then. span <= 2e9 so the product fits int64.
    const std::int64_t span = static_cast<std::int64_t>(lim.max) - lim.min;
    cfg.home_travel = static_cast<std::int32_t>(std::clamp<std::int64_t>(2 * span, 1, xy_axis::kPosMax));
    cfg.home_position = home.value;
    if (!xy_axis::config_valid(cfg)) return d;
  }
  d.ok = true;
  return d;
}

Board::Board(const Hardware& hw)
    : hw_(hw),
      store_(hw.fram),
      drivers_{tmc::Driver(hw.tmc[0]), tmc::Driver(hw.tmc[1])},
      tmp117_(hw.i2c, xy_tmp117::kAddressGnd),
      gyro_(hw.i2c, xy_icm20789::kAddressAd0Low) {
  table_.install(c::CommandId::Nop, &Board::on_nop);
  table_.install(c::CommandId::Stop, &Board::on_stop);
  table_.install(c::CommandId::Jog, &Board::on_jog);
  table_.install(c::CommandId::Goto, &Board::on_goto);
  table_.install(c::CommandId::Move, &Board::on_move);
  table_.install(c::CommandId::GotoSlow, &Board::on_goto_slow);
  table_.install(c::CommandId::MoveSlow, &Board::on_move_slow);
  table_.install(c::CommandId::Home, &Board::on_home);
  table_.install(c::CommandId::SetFastSpeed, &Board::on_param_id<c::CommandId::SetFastSpeed>);
  table_.install(c::CommandId::SetSlowSpeed, &Board::on_param_id<c::CommandId::SetSlowSpeed>);
  table_.install(c::CommandId::SetAccel, &Board::on_param_id<c::CommandId::SetAccel>);
  table_.install(c::CommandId::SetStartSpeed, &Board::on_param_id<c::CommandId::SetStartSpeed>);
  table_.install(c::CommandId::SetPitch, &Board::on_param_id<c::CommandId::SetPitch>);
  table_.install(c::CommandId::SetSteps, &Board::on_param_id<c::CommandId::SetSteps>);
  table_.install(c::CommandId::SetMicrosteps, &Board::on_param_id<c::CommandId::SetMicrosteps>);
  table_.install(c::CommandId::SetIrun, &Board::on_param_id<c::CommandId::SetIrun>);
  table_.install(c::CommandId::SetIhold, &Board::on_param_id<c::CommandId::SetIhold>);
  table_.install(c::CommandId::PeriphOff, &Board::on_periph_off);
  table_.install(c::CommandId::PeriphOn, &Board::on_periph_on);
  table_.install(c::CommandId::SaveParams, &Board::on_save);
  table_.install(c::CommandId::ClearFault, &Board::on_clear);
  table_.install(c::CommandId::PathLine, &Board::on_path_part<c::CommandId::PathLine>);
  table_.install(c::CommandId::PathCentre, &Board::on_path_part<c::CommandId::PathCentre>);
  table_.install(c::CommandId::PathArcCw, &Board::on_path_part<c::CommandId::PathArcCw>);
  table_.install(c::CommandId::PathArcCcw, &Board::on_path_part<c::CommandId::PathArcCcw>);
  table_.install(c::CommandId::PathEnd, &Board::on_path_end);
  derived_ = derive(store_.current());
}

BootResult Board::boot() {
  BootResult r{};
  r.store = store_.boot();
  derived_ = derive(store_.current());
  if (!derived_.ok) {
    // A set that passed its CRC and range checks but does not convert (e.g. a speed above
    // the step generator's range for this pitch) is not used; the defaults always convert.
    derived_ = derive(st::defaults());
    fault_ = kFaultBadParams;
  }
  r.drivers_ok = true;
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto init = drivers_[i].init();
    if (!init) {
      driver_fault(i, init.error());
      r.drivers_ok = false;
    }
  }
  // Both drivers are configured even if one fails, so a single bad chip does not leave the
  // other at its reset value (TOFF = 0: power stage off; docs/tmc2130.md "Boot configuration").
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto setup = configure_driver(drivers_[i], store_.current());
    if (!setup) {
      driver_fault(i, setup.error());
      r.drivers_ok = false;
    }
  }

  if (hw_.sample != nullptr) hw_.sample(hw_.ctx, in_);
  const st::ParameterSet& p = store_.current();
  const std::array<std::int32_t, kAxes> saved{p.step_count_x, p.step_count_y};
  const auto rev = static_cast<std::int32_t>(xy_axis::usteps_per_rev(derived_.mech));
  for (std::size_t i = 0; i < kAxes; ++i) {
    r.start[i] = xy_axis::start_position(&in_.encoder[i], {saved[i], p.step_counts_valid ? std::uint8_t{1} : std::uint8_t{0}},
                                      rev);
    axes_[i] = xy_axis::initial_state(r.start[i]);
    // An endstop active at power-up may be the switch the carriage rests on: it is latched
    // like one seen while moving, so a bouncing Hall switch cannot let the first move run
    // into it before the carriage has stepped away (docs/motion.md §4, G8).
    axes_[i].latch_min = in_.endstop_min[i] != 0 ? 1 : 0;
    axes_[i].latch_max = in_.endstop_max[i] != 0 ? 1 : 0;
  }
  // Last, so a sensor that fails its configure() shows its fault rather than being hidden
  // behind a storage or driver fault of the same boot.
  configure_temperature();
  configure_gyro();
  return r;
}

void Board::uart_rx(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    if (rx_count_ == rx_.size()) {
      ++counters_.rx_overruns;
      continue;
    }
    rx_[(rx_head_ + rx_count_) % rx_.size()] = b;
    ++rx_count_;
  }
}

void Board::tick() {
  if (powered_off_) return;  // the KillSwitch is pulled; only a power cycle brings the core back
  ++ticks_;
  param_cycle_ = false;
  frame_this_cycle_ = false;
  taken_this_cycle_ = false;
  echo_count_ = 0;
  pending_.fill(xy_axis::Command{});
  pending_id_.fill(c::CommandId::Nop);
  refused_.fill(kNoRefusal);
  path_error_ = xy_path::Error::None;
  begin_of_cycle();
  if (in_.button && !button_was_ && !off_requested_) request_off();
  button_was_ = in_.button;
  receive();
  step_axes();
  check_drivers();
  read_sensors();
  main_state_ = block_ != Block::None ? MainState::Blocked : (param_cycle_ ? MainState::ParamSet : MainState::UserControl);
  // The refusals are final once the axes have stepped (the axis core refuses too).
  if (taken_this_cycle_) last_outcome_ = Outcome{block_, refused_};
  send_echoes();
  if (hw_.led != nullptr) {
    const Led l = led();
    hw_.led(hw_.ctx, led_lit(l, ticks_) ? l.colour : LedColour::Off);
  }
  if (off_requested_ && !moving(axes_[0]) && !moving(axes_[1]) && !path_.active()) finish_shutdown();
}

// Thesis §7.9.5: an off request from the button's controller lets the firmware run a shutdown
// sequence that may save data to FRAM, then the MCU switches itself off through the KillSwitch.
// The axes get the ramped stop `sleep` gives (so the counter saved is where the carriage
// stands), motion is refused from then on, and the sequence ends at the first tick both axes
// stand (docs/board.md "Button and shutdown").
void Board::request_off() {
  off_requested_ = true;
  (void)on_periph_off(this, Axis::X, 0);
}

void Board::finish_shutdown() {
  // The step counters go to FRAM with their validity flag (§7.7.2 "FRAM alternative"): the
  // next boot starts from them when no encoder answers. A failed save latches its fault and
  // the unit still switches off: the user asked for it, and the next boot then starts
  // unhomed (the flag was not written) rather than from a wrong counter.
  (void)shutdown();
  powered_off_ = true;
  if (hw_.power_off != nullptr) hw_.power_off(hw_.ctx);
}

void Board::begin_of_cycle() {
  if (hw_.sample != nullptr) hw_.sample(hw_.ctx, in_);
  const std::uint16_t threshold = store_.current().low_battery_mv;
  if (in_.battery_mv < threshold) {
    battery_low_ = true;
  } else if (static_cast<std::uint32_t>(in_.battery_mv) >= static_cast<std::uint32_t>(threshold) + kBatteryHysteresisMv) {
    battery_low_ = false;
  }
  const Block was = block_;
  block_ = in_.usb ? Block::Usb : (in_.charger ? Block::Charger : (battery_low_ ? Block::Battery : Block::None));
  if (was != Block::None && block_ == Block::None) {
    // G16: back to user control with every axis at rest and nothing pending; the axis core
    // already dropped each axis's mode while blocked, so only the board's memory is cleared.
    for (std::size_t i = 0; i < kAxes; ++i) {
      axes_[i].mode = xy_axis::Mode::Idle;
      axes_[i].target = axes_[i].pos;
      event_[i] = AxisEvent::None;
    }
  }
  session_open_ = ble_state(in_.ble_status1, in_.ble_status2) == BleState::Session;
}

void Board::receive() {
  // At most one new frame is taken per cycle (docs/protocol.md "Two frames in one cycle"): the
  // handlers only store this cycle's motion command and the axes apply it when they step, so
  // a second new frame would replace the first one unrun while both were answered. The bytes
  // behind a taken frame wait in the ring for the next cycle (1 ms later); repeats, older
  // frames and rejections before it are answered in this cycle as usual.
  while (rx_count_ > 0 && echo_count_ < echoes_.size() && !taken_this_cycle_) {
    const std::uint8_t b = rx_[rx_head_];
    rx_head_ = (rx_head_ + 1) % rx_.size();
    --rx_count_;
    if (auto e = framer_.push(b)) handle(*e);
  }
}

void Board::handle(const xy_frame::RawCommandFramer::Event& e) {
  if (!e.rejection.ok()) {
    // A malformed frame is answered but changes nothing else: no handler, no watchdog
    // refresh, last_seq kept (docs/protocol.md, "What a rejected frame may change").
    if (!session_open_) return;
    echoes_[echo_count_++] = PendingEcho{true, e.rejection, last_seq_, {}, false};
    return;
  }
  if (!session_open_) {
    // G15: only a Data Session carries commands; bytes seen otherwise are line noise from
    // the module's own traffic and nobody is listening for an answer.
    ++counters_.gated_frames;
    return;
  }
  // The frame arrived intact; the callback table decides whether it means anything (an ID
  // outside the table, data out of range, an empty slot). Such a frame is rejected like a
  // malformed one, blocked or not.
  const xy_frame::Lookup found = table_.lookup(e.frame);
  if (const xy_frame::Rejection r = found.rejection; !r.ok()) {
    ++counters_.unhandled_frames;
    echoes_[echo_count_++] = PendingEcho{true, r, last_seq_, {}, false};
    return;
  }
  // Delivery (docs/protocol.md "Delivery"): the client repeats a frame until it is answered,
  // and the link may duplicate, delay and reorder, so a frame runs only when its seq is newer
  // than the last one taken. A repeat is answered with that frame's outcome and still proves
  // the link (the watchdog is fed, as by the frame itself); an older frame is answered with the
  // seq of the last one taken, which tells its sender where the board stands.
  const xy_codec::SeqOrder order = have_seq_ ? xy_codec::seq_order(last_seq_, e.frame.seq) : xy_codec::SeqOrder::New;
  if (order != xy_codec::SeqOrder::New) {
    if (order == xy_codec::SeqOrder::Repeat) {
      ++counters_.repeated_frames;
      if (block_ == Block::None) frame_this_cycle_ = true;
    } else {
      ++counters_.older_frames;
    }
    echoes_[echo_count_++] = PendingEcho{false, {}, last_seq_, e.frame.subs, true};
    return;
  }
  have_seq_ = true;
  last_seq_ = e.frame.seq;
  taken_this_cycle_ = true;
  if (hw_.frame_taken != nullptr) hw_.frame_taken(hw_.ctx, e.frame);
  if (block_ != Block::None) {
    // §7.5.2: commands cannot change the blocked state, so none is executed; the echo still
    // goes out so the PC can show why the unit does not move.
    ++counters_.blocked_frames;
    echoes_[echo_count_++] = PendingEcho{false, {}, e.frame.seq, e.frame.subs, false};
    return;
  }
  const xy_frame::DispatchResult r = table_.dispatch(found, e.frame, this);
  ++counters_.dispatched_frames;
  if (r.x == HandlerStatus::Refused) ++counters_.refused_parts;
  if (r.y == HandlerStatus::Refused) ++counters_.refused_parts;
  commit_path_frame(e.frame);
  frame_this_cycle_ = true;
  echoes_[echo_count_++] = PendingEcho{false, {}, e.frame.seq, e.frame.subs, false};
}

void Board::step_axes() {
  const bool was_alive = xy_axis::link_alive(watchdog_);
  watchdog_ = xy_axis::watchdog_tick(watchdog_, frame_this_cycle_);
  const bool alive = xy_axis::link_alive(watchdog_);
  if (was_alive && !alive) ++counters_.watchdog_expiries;
  if (path_.active()) {
    // The path drives both axes; their own motion commands are refused meanwhile.
    step_path(alive);
    return;
  }
  for (std::size_t i = 0; i < kAxes; ++i) {
    xy_axis::Input in;
    in.cmd = pending_[i];
    in.endstop_min = in_.endstop_min[i] != 0 ? 1 : 0;
    in.endstop_max = in_.endstop_max[i] != 0 ? 1 : 0;
    in.blocked = block_ != Block::None ? 1 : 0;
    // G15: a closed session is a lost link just like silence.
    in.link_alive = alive && session_open_ ? 1 : 0;
    const xy_axis::State before = axes_[i];
    const xy_axis::StepResult r = xy_axis::step(before, in, derived_.cfg[i]);
    axes_[i] = r.state;
    // This tick's command took effect unless the axis core refused it; a refused command
    // changed nothing and is its own echo, so it neither starts nor hides an event.
    const bool refused = in.cmd.kind != xy_axis::CmdKind::None && r.out.error != xy_axis::Error::None;
    const bool took = in.cmd.kind != xy_axis::CmdKind::None && !refused;
    if (refused) {
      refused_[i] = static_cast<std::uint8_t>(pending_id_[i]);
      ++counters_.refused_parts;
    } else if (in.cmd.kind == xy_axis::CmdKind::Stop) {
      // The echo shows the event that ended the last motion (docs/board.md "Echo content"):
      // a stop ends one only if the axis was moving or held a mode; at rest it changes
      // nothing, so a REACHED stays REACHED (docs/echo-model.md).
      if (moving(before) || before.mode != xy_axis::Mode::Idle) event_[i] = AxisEvent::StoppedByUser;
    } else if (took) {
      event_[i] = AxisEvent::None;  // an accepted motion command starts a new motion
    }
    const xy_axis::Edge edge = r.out.edge;
    if (edge == xy_axis::Edge::G || edge == xy_axis::Edge::H) {
      // Homing reached its reference only if the axis core took it (a stop in the same tick
      // ends the homing first: then it is a plain endstop stop; docs/echo-model.md).
      // The Home may also be this tick's command, given while moving down onto the switch.
      const bool homing = before.mode == xy_axis::Mode::Home || in.cmd.kind == xy_axis::CmdKind::Home;
      // A move whose carriage the switch halts on the move's own target reached what was
      // asked: REACHED is standing at the target, as for a stop in the tick of arrival
      // (docs/echo-model.md). The move is this tick's accepted goto / move, or the one held.
      const bool move = took ? (in.cmd.kind == xy_axis::CmdKind::MoveAbs || in.cmd.kind == xy_axis::CmdKind::MoveRel)
                             : before.mode == xy_axis::Mode::Position;
      const bool homed_here = homing && edge == xy_axis::Edge::G && r.state.homed != 0;
      const bool on_target = move && r.state.pos == r.state.target;
      event_[i] = homed_here || on_target ? AxisEvent::Reached : AxisEvent::Endstop;
    } else if (r.out.error == xy_axis::Error::HomeFailed) {
      event_[i] = AxisEvent::HomeFailed;
    } else if (before.mode == xy_axis::Mode::Jog && r.state.mode == xy_axis::Mode::Idle && in.link_alive == 0 &&
               in.cmd.kind == xy_axis::CmdKind::None) {
      event_[i] = AxisEvent::LinkLost;
    } else if (before.mode == xy_axis::Mode::Position && r.state.mode == xy_axis::Mode::Idle && r.state.pos == before.target &&
               !moving(r.state)) {
      // Reached means standing at the target: a stop that ends a move while the carriage
      // passes over its target still brakes beyond it, and stays STOPPED (docs/echo-model.md).
      event_[i] = AxisEvent::Reached;
    } else if (before.mode == xy_axis::Mode::Position && r.state.mode == xy_axis::Mode::Idle && !moving(before) &&
               !took && in.blocked == 0) {
      // A move standing short of its target (the reversal stop of a move that turned round)
      // whose way on is closed by an active or latched endstop: the axis core drops it (edge
      // I, motion.md §4), and the endstop is what ended it (docs/echo-model.md).
      event_[i] = AxisEvent::Endstop;
    } else if (r.state.mode == xy_axis::Mode::Position && !moving(r.state) && r.state.pos == r.state.target) {
      // Standing on the target of a move: the axis core halted there this tick (at or below
      // the start speed it may stop at once) and drops the finished move only on the next
      // tick (edge I), but the echo of this tick already describes a carriage standing at its
      // target: REACHED (docs/echo-model.md).
      event_[i] = AxisEvent::Reached;
    } else if ((in.cmd.kind == xy_axis::CmdKind::MoveAbs || in.cmd.kind == xy_axis::CmdKind::MoveRel) &&
               r.out.error == xy_axis::Error::None && r.state.mode == xy_axis::Mode::Idle && !moving(r.state) &&
               r.state.pos == r.state.target) {
      // A move to where the carriage already is: the requested position is reached
      // (docs/echo-model.md), not "standing, no target". Only there: a move the axis core
      // dropped in the same tick (a jog stopping hard at its soft limit) reached nothing.
      event_[i] = AxisEvent::Reached;
    } else if ((before.mode == xy_axis::Mode::Home || (in.cmd.kind == xy_axis::CmdKind::Home && r.out.error == xy_axis::Error::None)) &&
               r.state.mode == xy_axis::Mode::Idle && r.state.homed != 0 && !moving(r.state)) {
      // (A command of this tick the core refused does not hide a homing that completed.)
      // Homing that completes at standstill (switch already active, motion.md §6) is the same
      // completed reference as the G edge above: REACHED (docs/echo-model.md).
      event_[i] = AxisEvent::Reached;
    }
    // A completed reference makes where the carriage stands the axis's home position for good:
    // the absolute encoder is programmed so that it reads that position from now on, across
    // power cycles (thesis §7.7.2: the encoder's programmed zero is the absolute zero;
    // docs/motion.md "Homing and the encoder zero").
    const bool homing = before.mode == xy_axis::Mode::Home || in.cmd.kind == xy_axis::CmdKind::Home;
    if (homing && r.state.mode != xy_axis::Mode::Home && event_[i] == AxisEvent::Reached && hw_.encoder_zero != nullptr) {
      hw_.encoder_zero(hw_.ctx, static_cast<Axis>(i), encoder_counts_at(r.state.pos));
    }
    edge_[i] = r.out.edge;
    error_[i] = r.out.error;
    MotorOutput& m = motor_[i];
    m.dir = r.out.dir;
    m.steps = r.out.steps;
    m.step_hz = static_cast<std::uint32_t>(r.out.step_speed / xy_axis::kSpeedScale);
    // G24: asleep, the drivers are switched off once the carriage stands; blocked they keep
    // their hold current so the platform cannot be pushed off its counted position.
    m.enable = !(sleeping_ && !moving(r.state) && r.out.steps == 0);
    if (hw_.motor != nullptr) hw_.motor(hw_.ctx, static_cast<Axis>(i), m);
  }
}

std::int64_t Board::encoder_counts_at(std::int32_t pos) const {
  return xy_axis::encoder_counts_for(pos, static_cast<std::int32_t>(xy_axis::usteps_per_rev(derived_.mech)));
}

void Board::check_drivers() {
  // One GSTAT read per driver every 100 ms, staggered, restores the registers after a chip
  // reset (motor supply dip) without loading the SPI bus every tick.
  const std::uint32_t phase = ticks_ % kDriverCheckPeriod;
  for (std::size_t i = 0; i < kAxes; ++i) {
    if (phase != i * (kDriverCheckPeriod / kAxes)) continue;
    const auto r = drivers_[i].check_reset();
    if (!r) driver_fault(i, r.error());
  }
}

// ---- I2C sensors (docs/sensors.md "What the board does on an I2C error") ----------------
// After the axes: an I2C transaction may take a few hundred microseconds, and the step
// outputs of the tick must not wait for it. Before the echoes, so they carry this tick's
// angle and any fault a sensor latched in it.

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

void Board::send_echoes() {
  const xy_frame::EchoSource now{this, &Board::echo_axis, &Board::echo_subscriber};
  const xy_frame::EchoSource replay{this, &Board::echo_axis_replay, &Board::echo_subscriber};
  for (std::size_t k = 0; k < echo_count_; ++k) {
    const PendingEcho& p = echoes_[k];
    const xy_frame::EchoFrame echo = p.rejected ? xy_frame::build_rejection_echo(p.seq, p.rejection)
                                             : xy_frame::build_echo(p.seq, p.subs, p.replay ? replay : now);
    std::array<std::uint8_t, c::kEchoLength> out{};
    // build_* clamp every value into its table range, so formatting cannot fail.
    if (!xy_frame::format_echo(echo, out).ok()) continue;
    ++counters_.echoes_sent;
    if (hw_.uart_tx != nullptr) hw_.uart_tx(hw_.ctx, out);
  }
  echo_count_ = 0;
}

ShutdownResult Board::shutdown() {
  if (moving(axes_[0]) || moving(axes_[1]) || path_.active()) return ShutdownResult::Moving;
  const st::SaveResult r = store_.record_shutdown(axes_[0].pos, axes_[1].pos);
  if (!r.ok()) {
    fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
    return ShutdownResult::StorageFault;
  }
  return ShutdownResult::Ok;
}

BoardCounters Board::counters() const {
  BoardCounters k = counters_;
  k.framer = framer_.counters();
  return k;
}

std::int32_t Board::position_um(Axis a) const {
  return clamp32(xy_axis::usteps_to_um(axes_[idx(a)].pos, derived_.mech));
}

xy_frame::AxisEcho Board::axis_echo(Axis a) const { return echo_of(idx(a), block_, refused_[idx(a)]); }

xy_frame::AxisEcho Board::echo_of(std::size_t i, Block block, std::uint8_t refused) const {
  const xy_axis::State& s = axes_[i];
  const std::int32_t um = position_um(static_cast<Axis>(i));
  switch (block) {
    case Block::Usb: return {c::EchoStatus::BlockedUsb, um};
    case Block::Charger: return {c::EchoStatus::BlockedCharger, um};
    case Block::Battery: return {c::EchoStatus::BlockedBattery, um};
    case Block::None: break;
  }
  // The answer to a frame says first what became of its command (docs/board.md "Echo
  // content"): a refusal hidden behind a standing fault would read as "done". The fault shows
  // on every other echo.
  if (refused != kNoRefusal) return {c::EchoStatus::CommandRefused, refused};
  if (fault_ != 0) return {c::EchoStatus::Fault, fault_};
  if (sleeping_) return {c::EchoStatus::Sleeping, um};
  if (moving(s)) {
    if (s.mode == xy_axis::Mode::Home) return {c::EchoStatus::Homing, um};
    switch (s.phase) {
      case xy_axis::Phase::Accel: return {c::EchoStatus::Accelerating, um};
      case xy_axis::Phase::Decel: return {c::EchoStatus::Decelerating, um};
      default: return {c::EchoStatus::ConstantSpeed, um};
    }
  }
  switch (event_[i]) {
    case AxisEvent::Reached: return {c::EchoStatus::TargetReached, um};
    case AxisEvent::StoppedByUser: return {c::EchoStatus::StoppedByUser, um};
    case AxisEvent::Endstop: return {c::EchoStatus::EndstopHit, um};
    case AxisEvent::LinkLost: return {c::EchoStatus::LinkLost, um};
    case AxisEvent::HomeFailed:
    case AxisEvent::None: break;
  }
  return {c::EchoStatus::Idle, um};
}

std::int32_t Board::subscriber(xy_frame::SubscriberSlot slot) {
  const std::size_t ax = slot.arg < kAxes ? slot.arg : 0;
  switch (slot.id) {
    case c::SubscriberId::None: return 0;
    case c::SubscriberId::BatteryMv: return in_.battery_mv;
    case c::SubscriberId::ChargeMa: return in_.charge_ma;
    case c::SubscriberId::TemperatureMc: {
      // The register reaches -256 °C and the wire field stops at -99.999 °C: clamped, never
      // wrapped (docs/sensors.md "Wire range"). Every temperature in the sensor's specified
      // range fits.
      return std::clamp(temperature_mc_, kTemperatureWire.min, kTemperatureWire.max);
    }
    case c::SubscriberId::RotationMdeg: return rotation_.mdeg();
    case c::SubscriberId::EncoderUm: {
      const auto rev = static_cast<std::int32_t>(xy_axis::usteps_per_rev(derived_.mech));
      const xy_axis::StartPosition p = xy_axis::encoder_to_usteps(in_.encoder[ax], rev);
      return p.error == xy_axis::Error::None ? clamp32(xy_axis::usteps_to_um(p.pos, derived_.mech)) : 0;
    }
    case c::SubscriberId::DrvStatusLo:
    case c::SubscriberId::DrvStatusHi: {
      const auto r = drivers_[ax].read(tmc::Reg::DRV_STATUS);
      if (!r) return 0;
      return static_cast<std::int32_t>(slot.id == c::SubscriberId::DrvStatusLo ? (*r & 0xFFFFU) : (*r >> 16));
    }
    case c::SubscriberId::Param: {
      if (slot.arg >= st::kItemCount) return 0;
      const auto v = st::get_field(store_.current(), static_cast<st::ParamId>(slot.arg));
      return v ? clamp32(*v) : 0;
    }
    case c::SubscriberId::LinkStats: {
      const xy_frame::FramerCounters f = framer_.counters();
      switch (static_cast<c::LinkStat>(slot.arg)) {
        case c::LinkStat::AcceptedFrames: return wrap_million(f.accepted_frames);
        case c::LinkStat::RejectedFrames: return wrap_million(f.rejected_frames);
        case c::LinkStat::RejectedBytes: return wrap_million(f.rejected_bytes);
        case c::LinkStat::WatchdogExpiries: return wrap_million(counters_.watchdog_expiries);
      }
      return 0;
    }
  }
  return 0;
}

xy_frame::AxisEcho Board::echo_axis(void* ctx, Axis a) { return static_cast<const Board*>(ctx)->axis_echo(a); }

xy_frame::AxisEcho Board::echo_axis_replay(void* ctx, Axis a) {
  // A repeated or older frame: the outcome the last frame taken had when it was taken (its
  // block, its refusals) and the state now (docs/protocol.md "Delivery"). A block that came on
  // after the frame ran does not show: the client reads BLOCKED_* as "did not take effect",
  // and that frame did; the next new frame's answer shows the block.
  const auto* b = static_cast<const Board*>(ctx);
  const std::size_t i = idx(a);
  return b->echo_of(i, b->last_outcome_.block, b->last_outcome_.refused[i]);
}

std::int32_t Board::echo_subscriber(void* ctx, xy_frame::SubscriberSlot slot) {
  return static_cast<Board*>(ctx)->subscriber(slot);
}

// ---- handlers ---------------------------------------------------------------------------

xy_frame::HandlerStatus Board::refuse(Axis a, c::CommandId id) {
  refused_[idx(a)] = static_cast<std::uint8_t>(id);
  return HandlerStatus::Refused;
}

bool Board::motion_permitted() {
  if (sleeping_) return false;
  // The saved step counter stops being trustworthy the moment the carriage may move, so
  // its validity flag is cleared in FRAM (verified) before the first step; if that write
  // fails, the motion is refused rather than leaving a stale "valid" counter behind.
  const st::SaveResult r = store_.begin_motion();
  if (!r.ok()) {
    fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
    return false;
  }
  return true;
}

xy_frame::HandlerStatus Board::set_axis_command(Axis a, c::CommandId id, const xy_axis::Command& cmd) {
  const std::size_t i = idx(a);
  pending_[i] = cmd;
  pending_id_[i] = id;
  return HandlerStatus::Done;
}

// What the axis core will do with this cycle's pending motion command (a dry run of its
// command check on a copy of the state: the core decides, the board does not re-implement it).
Board::Pending Board::pending_motion(std::size_t i) const {
  if (pending_[i].kind == xy_axis::CmdKind::None || pending_[i].kind == xy_axis::CmdKind::Stop) return Pending::None;
  xy_axis::Input dry;
  dry.cmd = pending_[i];
  dry.endstop_min = in_.endstop_min[i] != 0 ? 1 : 0;
  dry.endstop_max = in_.endstop_max[i] != 0 ? 1 : 0;
  dry.blocked = block_ != Block::None ? 1 : 0;
  dry.link_alive = 1;
  return xy_axis::step(axes_[i], dry, derived_.cfg[i]).out.error != xy_axis::Error::None ? Pending::Refused
                                                                                   : Pending::Accepted;
}

HandlerStatus Board::on_nop(void*, Axis, std::int32_t) { return HandlerStatus::Done; }

HandlerStatus Board::on_stop(void* ctx, Axis a, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  if (b->path_.active()) {
    // A stop of either axis stops the path: both axes share one S-curve (docs/cnc.md "Stops").
    b->stop_path_by_user();
    return HandlerStatus::Done;
  }
  return b->set_axis_command(a, c::CommandId::Stop, {xy_axis::CmdKind::Stop, 0, 0, 0});
}

HandlerStatus Board::on_jog(void* ctx, Axis a, std::int32_t data) {
  auto* b = static_cast<Board*>(ctx);
  if (b->path_.active()) return b->refuse(a, c::CommandId::Jog);  // the path holds both axes
  if (data == 0) return b->set_axis_command(a, c::CommandId::Jog, {xy_axis::CmdKind::Stop, 0, 0, 0});
  if (!b->motion_permitted()) return b->refuse(a, c::CommandId::Jog);
  const std::int8_t dir = data > 0 ? std::int8_t{1} : std::int8_t{-1};
  const std::uint8_t level = (data == c::kJogFast || data == -c::kJogFast) ? 1 : 0;
  return b->set_axis_command(a, c::CommandId::Jog, {xy_axis::CmdKind::Jog, dir, level, 0});
}

HandlerStatus Board::on_goto(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_absolute(a, c::CommandId::Goto, um, kLevelFast);
}
HandlerStatus Board::on_goto_slow(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_absolute(a, c::CommandId::GotoSlow, um, kLevelSlow);
}
HandlerStatus Board::on_move(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_relative(a, c::CommandId::Move, um, kLevelFast);
}
HandlerStatus Board::on_move_slow(void* ctx, Axis a, std::int32_t um) {
  return static_cast<Board*>(ctx)->position_relative(a, c::CommandId::MoveSlow, um, kLevelSlow);
}

// Thesis §7.7 and §8.2.2: both speed levels serve manual moves and positioning; goto/move run
// at the fast level, goto_slow/move_slow at the slow one (docs/protocol.md, the command table).
HandlerStatus Board::position_absolute(Axis a, c::CommandId id, std::int32_t um, std::uint8_t level) {
  if (path_.active()) return refuse(a, id);  // the path holds both axes
  const st::ParameterSet& p = store_.current();
  const bool x = a == Axis::X;
  const xy_axis::Converted t =
      xy_axis::target_to_usteps(um, x ? p.soft_min_x_um : p.soft_min_y_um, x ? p.soft_max_x_um : p.soft_max_y_um, derived_.mech);
  if (t.error != xy_axis::Error::None) return refuse(a, id);
  if (!motion_permitted()) return refuse(a, id);
  return set_axis_command(a, id, {xy_axis::CmdKind::MoveAbs, 0, level, t.value});
}

HandlerStatus Board::position_relative(Axis a, c::CommandId id, std::int32_t um, std::uint8_t level) {
  if (path_.active()) return refuse(a, id);  // the path holds both axes
  const xy_axis::Converted d = xy_axis::um_to_usteps(um, derived_.mech, xy_axis::Round::Nearest);
  if (d.error != xy_axis::Error::None) return refuse(a, id);
  if (!motion_permitted()) return refuse(a, id);
  return set_axis_command(a, id, {xy_axis::CmdKind::MoveRel, 0, level, d.value});
}

HandlerStatus Board::on_home(void* ctx, Axis a, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  if (b->path_.active()) return b->refuse(a, c::CommandId::Home);  // the path holds both axes
  // Homing mode 1 (towards the min endstop) is the only one built: 0 means the platform has no
  // homing, 2 (StallGuard) needs a calibration the thesis does not give and a DIAG1 input the
  // board does not read (docs/storage.md "Factory and user parameters").
  if (b->store_.current().homing_mode != kHomingModeEndstop) return b->refuse(a, c::CommandId::Home);
  if (!b->motion_permitted()) return b->refuse(a, c::CommandId::Home);
  return b->set_axis_command(a, c::CommandId::Home, {xy_axis::CmdKind::Home, 0, 0, 0});
}

HandlerStatus Board::on_param(void* ctx, Axis a, std::int32_t value, c::CommandId id) {
  auto* b = static_cast<Board*>(ctx);
  st::ParamId pid = st::ParamId::MaxAcceleration;
  switch (id) {
    case c::CommandId::SetFastSpeed: pid = st::ParamId::FastSpeed; break;
    case c::CommandId::SetSlowSpeed: pid = st::ParamId::SlowSpeed; break;
    case c::CommandId::SetAccel: pid = st::ParamId::MaxAcceleration; break;
    case c::CommandId::SetStartSpeed: pid = st::ParamId::StartSpeed; break;
    case c::CommandId::SetPitch: pid = st::ParamId::LeadPitch; break;
    case c::CommandId::SetSteps: pid = st::ParamId::StepsPerRev; break;
    case c::CommandId::SetMicrosteps: pid = st::ParamId::Microsteps; break;
    case c::CommandId::SetIrun: pid = st::ParamId::RunCurrent; break;
    case c::CommandId::SetIhold: pid = st::ParamId::HoldCurrent; break;
    default: return b->refuse(a, id);
  }
  return b->set_parameter(a, id, pid, value);
}

HandlerStatus Board::set_parameter(Axis a, c::CommandId id, st::ParamId pid, std::int32_t value) {
  param_cycle_ = true;
  const bool current = pid == st::ParamId::RunCurrent || pid == st::ParamId::HoldCurrent;
  // A queued path was converted and planned with the parameters in force (docs/cnc.md).
  if (path_.active() && !current) return refuse(a, id);
  st::ParameterSet next = store_.current();
  if (!st::set_field(next, pid, value) || !st::validate(next).ok()) return refuse(a, id);
  const Derived d = derive(next);
  if (!d.ok) return refuse(a, id);
  const bool mechanics = pid == st::ParamId::LeadPitch || pid == st::ParamId::StepsPerRev || pid == st::ParamId::Microsteps;
  const bool currents = pid == st::ParamId::RunCurrent || pid == st::ParamId::HoldCurrent;
  // Only the currents may change under a moving carriage. A move is planned with the speeds
  // and acceleration it started with: a lower deceleration mid-move would carry the axis
  // past a target it could reach before (found by fuzz/xy/board), and changed mechanics would
  // make the step counter and the target meaningless.
  // At rest also means no motion command earlier in this frame: its distance was converted
  // with the mechanics in force when its handler ran, and a pitch or microstep change would
  // rescale the counter under it (a -60 mm move became -3.75 mm; docs/echo-model.md).
  // At rest also means holding no motion: a jog held at its reversal stop or at a soft limit
  // steps again on the next tick, and the mechanics change below would drop its mode without
  // an event (docs/echo-model.md).
  // A move standing on its target is finished (REACHED; the axis core drops it on the next
  // tick, edge I): it holds nothing.
  const auto finished = [this](std::size_t k) {
    return axes_[k].mode == xy_axis::Mode::Position && axes_[k].pos == axes_[k].target;
  };
  const auto holds = [this, &finished](std::size_t k) {
    return moving(axes_[k]) || (axes_[k].mode != xy_axis::Mode::Idle && !finished(k));
  };
  if (!currents && (holds(0) || holds(1) ||
                    (mechanics && (pending_motion(0) == Pending::Accepted || pending_motion(1) == Pending::Accepted)))) {
    return refuse(a, id);
  }
  // A pending motion command the axis core will refuse keeps its refusal now: a change of
  // the mechanics below would rescale the counter under its converted distance.
  for (std::size_t k = 0; k < kAxes; ++k) {
    if (mechanics && pending_motion(k) == Pending::Refused) {
      refused_[k] = static_cast<std::uint8_t>(pending_id_[k]);
      pending_[k] = {};
    }
  }
  const st::SaveResult r = store_.save(next);
  if (!r.ok()) {
    // The store keeps using the previous verified set; so does the board.
    fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
    return HandlerStatus::Done;
  }
  if (mechanics) {
    for (std::size_t i = 0; i < kAxes; ++i) {
      const std::int64_t um = xy_axis::usteps_to_um(axes_[i].pos, derived_.mech);
      const xy_axis::Converted p = xy_axis::um_to_usteps(clamp32(um), d.mech, xy_axis::Round::Nearest);
      if (p.error == xy_axis::Error::None) {
        axes_[i].pos = p.value;
      } else {
        axes_[i].homed = 0;  // not representable any more: the axis must home again
      }
      axes_[i].target = axes_[i].pos;
      axes_[i].mode = xy_axis::Mode::Idle;
      axes_[i].frac = 0;
    }
  }
  derived_ = d;
  if (pid == st::ParamId::RunCurrent || pid == st::ParamId::HoldCurrent) (void)apply_currents();
  if (pid == st::ParamId::Microsteps) (void)apply_microsteps();
  return HandlerStatus::Done;
}

bool Board::apply_currents() {
  const st::ParameterSet& p = store_.current();
  bool ok = true;
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto r = drivers_[i].update(tmc::Reg::IHOLD_IRUN, {{tmc::Field::IHOLD_IRUN_IHOLD, p.hold_current_cs},
                                                             {tmc::Field::IHOLD_IRUN_IRUN, p.run_current_cs}});
    if (!r) {
      driver_fault(i, r.error());
      ok = false;
    }
  }
  return ok;
}

bool Board::apply_microsteps() {
  const std::int64_t mres = mres_of(store_.current().microsteps);
  bool ok = true;
  for (std::size_t i = 0; i < kAxes; ++i) {
    const auto r = drivers_[i].set(tmc::Field::CHOPCONF_MRES, mres);
    if (!r) {
      driver_fault(i, r.error());
      ok = false;
    }
  }
  return ok;
}

void Board::driver_fault(std::size_t i, tmc::Error e) {
  fault_ = (i == 0 ? kFaultDriverX : kFaultDriverY) + static_cast<std::int32_t>(e);
}

HandlerStatus Board::on_periph_off(void* ctx, Axis, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  b->sleeping_ = true;
  // Sleep stops the path as `stop` does (docs/cnc.md "Stops"), here in the handler: a path
  // that has not moved yet drops its queue at once, so a command later in the same frame
  // finds no path (docs/echo-model.md "The coordinated path").
  if (b->path_.active()) b->stop_path_by_user();
  for (std::size_t i = 0; i < kAxes; ++i) {
    // A motion command earlier in this frame that the axis core would refuse (out of the
    // soft limits, toward an endstop, ...) is still reported as refused: the stop replaces
    // it, but the PC must not lose the typed error (docs/board.md "Echo content",
    // docs/echo-model.md "Decisions").
    if (b->pending_motion(i) == Pending::Refused) b->refused_[i] = static_cast<std::uint8_t>(b->pending_id_[i]);
    b->pending_[i] = {xy_axis::CmdKind::Stop, 0, 0, 0};
    b->pending_id_[i] = c::CommandId::PeriphOff;
  }
  return HandlerStatus::Done;
}

HandlerStatus Board::on_periph_on(void* ctx, Axis, std::int32_t) {
  static_cast<Board*>(ctx)->sleeping_ = false;
  return HandlerStatus::Done;
}

HandlerStatus Board::on_save(void* ctx, Axis, std::int32_t) {
  auto* b = static_cast<Board*>(ctx);
  b->param_cycle_ = true;
  const st::SaveResult r = b->store_.save(b->store_.current());
  if (!r.ok()) b->fault_ = kFaultStorage + static_cast<std::int32_t>(r.status);
  return HandlerStatus::Done;
}

HandlerStatus Board::on_clear(void* ctx, Axis, std::int32_t) {
  static_cast<Board*>(ctx)->fault_ = 0;
  return HandlerStatus::Done;
}

}  // namespace ap::xy_board
