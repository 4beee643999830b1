#include "replay.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/xy/axis/step_timer.hpp"
#include "core/xy/axis/watchdog.hpp"

namespace smt_replay {

namespace ax = ap::xy_axis;

namespace {

// Reference stopping distance (fine units): the sum of the braking ticks above the start
// speed, written independently of stop_distance_fine (ceil form, 128-bit).
std::int64_t ref_dd(std::int64_t v, std::int64_t s, std::int64_t a) {
  if (v <= s) return 0;
  const std::int64_t m = (v - s + a - 1) / a - 1;
  return m * v - static_cast<std::int64_t>(a) * m * (m + 1) / 2;
}

std::string timer_violations(unsigned f) {
  std::ostringstream o;
  const auto t = ax::step_timer(f);
  if (!t) return "no setting for an in-range frequency\n";
  const std::uint64_t p = std::uint64_t{t->psc} + 1, a = std::uint64_t{t->arr} + 1;
  const std::uint64_t clk = ax::kTimerClockHz;
  // With 16-bit registers the realised frequency must bracket the request as documented.
  if (!(f * p * a <= clk && clk < f * p * (a + 1))) o << "f=" << f << ": realised frequency outside [f, f*(ARR+2)/(ARR+1))\n";
  if (f < 1221 && a < 32768) o << "f=" << f << ": ARR+1=" << a << " < 32768\n";
  if (f >= 1221 && t->psc != 0) o << "f=" << f << ": PSC=" << t->psc << " != 0\n";
  return o.str();
}

}  // namespace

// Every (phase, class) through the real edge_for: exactly one guard holds and it is the edge's.
std::string table_violations() {
  std::ostringstream o;
  for (int p = 0; p < ax::kPhaseCount; ++p) {
    for (int c = 0; c < ax::kClassCount; ++c) {
      const auto ph = static_cast<ax::Phase>(p);
      const auto cl = static_cast<ax::Class>(c);
      const ax::Edge e = ax::edge_for(ph, cl);
      int holding = 0;
      for (int x = 0; x < ax::kEdgeCount; ++x) holding += ax::edge_guard(static_cast<ax::Edge>(x), ph, cl) ? 1 : 0;
      if (!ax::edge_guard(e, ph, cl) || holding != 1)
        o << "phase " << p << " class " << c << ": edge " << ax::edge_letter(e) << " (guards holding: " << holding << ")\n";
    }
  }
  return o.str();
}

// The link watchdog after a valid frame and then silence: alive exactly for the first
// kLinkTimeoutTicks - 1 silent ticks, lost from tick kLinkTimeoutTicks on, and it stays lost.
std::string watchdog_violations() {
  std::ostringstream o;
  ax::LinkWatchdog w = ax::watchdog_tick(ax::LinkWatchdog{}, true);
  for (int t = 1; t <= 1000; ++t) {
    w = ax::watchdog_tick(w, false);
    if (ax::link_alive(w) != (t < ax::kLinkTimeoutTicks)) {
      o << "tick " << t << " after the last frame: link " << (ax::link_alive(w) ? "alive" : "lost") << "\n";
      break;
    }
  }
  return o.str();
}

std::string violations(const Case& k) {
  if (k.kind == "timer") return timer_violations(k.timer_f);
  if (k.kind == "table") return table_violations();
  if (k.kind == "watchdog") return watchdog_violations();
  std::ostringstream o;
  const ax::Config& c = k.config;
  const bool cfg_ok = ax::config_valid(c);
  const std::int64_t sf = std::int64_t{c.v_start} * ax::kSpeedScale;
  const std::int64_t vmax = std::int64_t{c.v_fast} * ax::kSpeedScale;
  ax::State s = k.state;
  // The move is "reachable" when the true stopping distance plus this tick fits before the target.
  auto room_to = [&](std::int64_t t) { return (t - s.pos) * s.dir * ax::kDistScale - s.frac; };
  const bool moving_pos = s.mode == ax::Mode::Position && s.phase != ax::Phase::Stop &&
                          (static_cast<std::int64_t>(s.target) - s.pos) * s.dir >= 1;
  bool reachable = moving_pos && (s.v <= sf || ref_dd(s.v, sf, c.accel) < room_to(s.target));
  std::int32_t target = s.target;
  // A case that opens with a move command: the obligation's input assumption (a move from rest,
  // or a retarget at least the stopping distance ahead in the direction of motion) decides.
  if (!k.inputs.empty() && (k.inputs[0].cmd.kind == ax::CmdKind::MoveAbs || k.inputs[0].cmd.kind == ax::CmdKind::MoveRel)) {
    const ax::Command& cmd = k.inputs[0].cmd;
    const std::int64_t t = cmd.kind == ax::CmdKind::MoveAbs ? cmd.value : std::int64_t{s.pos} + cmd.value;
    const int d_new = t > s.pos ? 1 : (t < s.pos ? -1 : 0);
    reachable = s.phase == ax::Phase::Stop || (d_new == s.dir && (s.v <= sf || ref_dd(s.v, sf, c.accel) < room_to(t)));
    if (t >= INT32_MIN && t <= INT32_MAX) target = static_cast<std::int32_t>(t);
  }
  const std::int32_t start = s.pos;
  // A stop with no frames (axis.watchdog.stop_distance): from Idle and moving, with no command
  // in the case, the carriage travels at most DD(v0) + one tick at start speed, in fine units.
  bool no_commands = true;
  for (const auto& in : k.inputs) no_commands = no_commands && in.cmd.kind == ax::CmdKind::None;
  // The same budget for a Position target that is not reachable (axis.position.overrun): behind,
  // at the carriage, or ahead closer than the stopping distance.
  const bool pos_unreachable =
      s.mode == ax::Mode::Position && ((static_cast<std::int64_t>(s.target) - s.pos) * s.dir < 1 ||
                                       (s.v > sf && ref_dd(s.v, sf, c.accel) >= room_to(s.target)));
  const bool stopping = cfg_ok && ax::state_valid(s) && no_commands &&
                        (s.mode == ax::Mode::Idle || pos_unreachable) && s.phase != ax::Phase::Stop;
  const std::int64_t stop_budget = s.v > sf ? ref_dd(s.v, sf, c.accel) + sf : 0;
  std::int64_t travelled = 0;
  const int total = static_cast<int>(k.inputs.size()) + k.run;
  for (int t = 0; t < total; ++t) {
    const ax::Input in = t < static_cast<int>(k.inputs.size()) ? k.inputs[static_cast<std::size_t>(t)] : ax::Input{};
    const bool valid_before = cfg_ok && ax::state_valid(s);
    const ax::StepResult r = ax::step(s, in, c);
    const ax::State& n = r.state;
    if (valid_before) {
      if (!ax::state_valid(n)) o << "tick " << t << ": state_valid broken\n";
      if (s.v <= vmax && (n.v > vmax || r.out.step_speed > vmax)) o << "tick " << t << ": speed " << n.v << " above v_fast\n";
      if (n.dir != s.dir && (s.v > sf || r.out.steps != 0))
        o << "tick " << t << ": DIR changed at speed " << s.v << " > start speed " << sf << "\n";
      if (r.out.steps > 0 && r.out.dir > 0 && (in.endstop_max != 0 || s.latch_max != 0)) o << "tick " << t << ": step toward max endstop\n";
      if (r.out.steps > 0 && r.out.dir < 0 && (in.endstop_min != 0 || s.latch_min != 0)) o << "tick " << t << ": step toward min endstop\n";
      if (s.homed != 0 && n.homed != 0 && in.cmd.kind != ax::CmdKind::Home &&
          (n.pos > std::max(s.pos, c.soft_max) || n.pos < std::min(s.pos, c.soft_min)))
        o << "tick " << t << ": soft limit crossed, pos " << s.pos << " -> " << n.pos << "\n";
      if (reachable && n.target == target && (s.mode == ax::Mode::Position || n.mode == ax::Mode::Position)) {
        if ((static_cast<std::int64_t>(target) - n.pos) * (static_cast<std::int64_t>(target) - start) < 0)
          o << "tick " << t << ": overshoot: pos " << n.pos << " passed target " << target << "\n";
        if (n.pos == target && s.pos != target && r.out.step_speed > sf)
          o << "tick " << t << ": arrival at speed " << r.out.step_speed << " > start speed " << sf << "\n";
      }
    }
    travelled += r.out.step_speed;
    // Checked every tick: the travel so far plus what the stop still needs at full deceleration
    // (so a stop that has already committed to too much travel fails at once, not after
    // millions of ticks).
    const std::int64_t still_needed = n.phase == ax::Phase::Stop ? 0 : (n.v > sf ? ref_dd(n.v, sf, c.accel) + sf : 0);
    if (stopping && travelled + still_needed > stop_budget) {
      o << "tick " << t << ": stop not complete within its distance: " << travelled << " fine units travelled + "
        << still_needed << " still needed > DD(v0) + s_fine = " << stop_budget << "\n";
      break;
    }
    s = n;
    if (t >= static_cast<int>(k.inputs.size()) && s.phase == ax::Phase::Stop) break;
  }
  return o.str();
}

std::vector<std::string> case_files(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".case") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace smt_replay
