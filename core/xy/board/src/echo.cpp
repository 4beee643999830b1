// The echoes of a cycle (docs/board.md "One cycle (tick) in order" step 8), built last from the
// state the rest of the board left, which they only read: each axis's status by priority
// (docs/board.md "Echo content"; docs/protocol.md "Echo statuses"), a repeat's answer with the
// outcome its frame had when taken (docs/protocol.md "Delivery"), the subscriber values
// (docs/protocol.md "Subscribers"; the temperature's wire range in docs/sensors.md, a stored
// parameter by its docs/storage.md map index), formatted and sent.
#include "core/xy/board/board.hpp"

#include <algorithm>

#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "core/xy/frame/echo_builder.hpp"
#include "core/xy/frame/echo_codec.hpp"

#include "helpers.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
namespace st = ap::xy_storage;
namespace tmc = ap::xy_tmc2130;

namespace {

constexpr std::int32_t wrap_million(std::uint32_t v) { return static_cast<std::int32_t>(v % 1'000'000U); }

// docs/protocol.md, the subscriber table: -99999 .. 999999 m°C (the table is indexed by ID).
constexpr c::Range kTemperatureWire = c::kSubscribers[static_cast<std::size_t>(c::SubscriberId::TemperatureMc)].range;

}  // namespace

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

}  // namespace ap::xy_board
