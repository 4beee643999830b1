// The echo the model expects for each frame event of the tick, and its comparison with the echo
// the board sent. Each axis's status by priority (docs/board.md "Echo content": BLOCKED_* >
// COMMAND_REFUSED > FAULT > SLEEPING > moving > the event that ended the last motion > IDLE), a
// rejected frame's answer (docs/protocol.md "What a rejected frame may change"), a repeat's
// answer with the outcome its frame had when taken (docs/protocol.md "Delivery": "What a repeat
// answers"), the subscriber packets (docs/protocol.md "Subscribers"; docs/storage.md's map
// ids). check() takes the position within 1 um of the step counter, or the field's nearest end
// beyond its range (docs/protocol.md "Echo statuses").
#include "models/xy/echo/echo_model.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "protocol/xy/codec/subscribers.hpp"

namespace ap::model::xy_echo {
namespace {

using xy_codec::CommandId;
using xy_codec::EchoStatus;

constexpr std::int32_t kTempWireMin = -99999;      // docs/protocol.md, subscriber "temp"
constexpr std::int32_t kTempWireMax = 999999;

std::string status_name(EchoStatus s) {
  const auto* info = xy_codec::find_status(static_cast<std::uint32_t>(s));
  return info != nullptr ? std::string(info->key) : "status" + std::to_string(static_cast<int>(s));
}

}  // namespace

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
