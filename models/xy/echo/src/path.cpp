// The coordinated path as the PC sees it (docs/cnc.md "From G-code to the axes", "On the
// board", "Stops", "Echoes"; the decisions where docs/cnc.md is silent are in
// docs/echo-model.md "The coordinated path"): a frame's path parts queued as one segment or
// stored as the next arc's centre, a stop (user, sleep, lost link, block) and whether it drops
// a standing path at once, and, once the path is observed at rest, the event that ended it.
// Whether a path frame is refused is path_verdict.cpp's.
#include "models/xy/echo/echo_model.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace ap::model::xy_echo {
namespace {

using xy_codec::CommandId;
using xy_codec::EchoStatus;

}  // namespace

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

void EchoModel::path_end_tick(const Motion& motion, const std::array<bool, kAxes>& halted_on_switch) {
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
  // the last segment it reached it, and short of it an endstop halted it. A switch that halts
  // the controlled stop of a user stop or a lost link ended it, as it ends a braking axis
  // (docs/echo-model.md "Decisions"); under a block the event is cleared anyway (G16).
  Ended e = Ended::None;
  const bool at_end = motion[0].pos == path_.end[0] && motion[1].pos == path_.end[1];
  const bool on_switch = halted_on_switch[0] || halted_on_switch[1];
  switch (path_.stop) {
    case PathStop::Block: e = Ended::None; break;
    case PathStop::User: e = on_switch ? Ended::Endstop : Ended::Stopped; break;
    case PathStop::Link: e = on_switch ? Ended::Endstop : Ended::LinkLost; break;
    case PathStop::None: e = at_end ? Ended::Reached : Ended::Endstop; break;
  }
  path_finish(e);
}

}  // namespace ap::model::xy_echo
