// The coordinated path on the board core (docs/cnc.md "On the board"): frames in, both axes
// out, the echo's events, the refusals, the stops, with the safety monitor (models/xy/safety) on
// every tick.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "models/xy/safety/board_monitor.hpp"
#include "protocol/xy/codec/commands.hpp"

namespace {

using ap::xy_board::Axis;
using ap::xy_board::AxisEvent;
using ap::sim::xy::Rig;
using C = ap::xy_codec::CommandId;
using S = ap::xy_codec::EchoStatus;

struct PathRig {
  Rig r;
  ap::model::xy_safety::BoardMonitor mon;
  std::vector<ap::model::xy_safety::Violation> violations;

  PathRig() {
    // Both axes know their position from their encoders (docs/board.md "Power-up").
    r.in.encoder[0] = {0, 0, 1};
    r.in.encoder[1] = {0, 0, 1};
    r.boot();
    mon.booted(*r.board);
  }
  void tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      mon.before_tick(*r.board);
      r.tick();
      mon.after_tick(*r.board, violations);
    }
  }
  // Frames every 100 ms keep the link watchdog fed (thesis §6.2), until the path is done.
  void run_until_idle(int max_ms = 60000) {
    for (int t = 0; t < max_ms && r.board->path().active(); t += 100) {
      r.send(C::Nop, 0, C::Nop, 0);
      tick(100);
    }
    EXPECT_FALSE(r.board->path().active()) << "the path did not finish in " << max_ms << " ms";
  }
  std::int32_t um(Axis a) const { return r.board->position_um(a); }
  S status(Axis a) const {
    const auto e = r.last_echo();
    return e ? (a == Axis::X ? e->x.status : e->y.status) : S::Idle;
  }
};

TEST(BoardPath, ALineFrameMovesBothAxesToItsEnd) {
  PathRig p;
  p.r.send(C::PathLine, 30000, C::PathLine, 10000);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(2);
  EXPECT_TRUE(p.r.board->path().active());
  p.run_until_idle();
  EXPECT_EQ(p.um(Axis::X), 30000);
  EXPECT_EQ(p.um(Axis::Y), 10000);
  EXPECT_EQ(p.r.board->axis_event(Axis::X), AxisEvent::Reached);
  EXPECT_EQ(p.r.board->axis_event(Axis::Y), AxisEvent::Reached);
  p.r.send(C::Nop, 0, C::Nop, 0);
  p.tick();
  EXPECT_EQ(p.status(Axis::X), S::TargetReached);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, AnArcNeedsItsCentreFrame) {
  PathRig p;
  p.r.send(C::PathArcCw, 20000, C::PathArcCw, 0);
  p.tick();
  EXPECT_EQ(p.r.board->path_error(), ap::xy_path::Error::NoCentre);
  EXPECT_EQ(p.status(Axis::X), S::CommandRefused);
  EXPECT_FALSE(p.r.board->path().active());
  // A half circle from (0,0) over (10,10) to (20,0) mm: centre 10 mm to the right.
  p.r.send(C::PathLine, 0, C::PathLine, 10000);  // to (0, 10) mm first
  p.r.send(C::PathCentre, 10000, C::PathCentre, 10000);
  p.r.send(C::PathArcCw, 20000, C::PathArcCw, 10000);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(4);
  p.run_until_idle();
  EXPECT_EQ(p.um(Axis::X), 20000);
  EXPECT_EQ(p.um(Axis::Y), 10000);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, NotHomedIsRefusedAndNothingMoves) {
  Rig r;
  r.boot();
  r.send(C::PathLine, 1000, C::PathLine, 1000);
  r.tick();
  EXPECT_EQ(r.board->path_error(), ap::xy_path::Error::NotHomed);
  const auto e = r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->x.status, S::CommandRefused);
  EXPECT_EQ(e->x.data, static_cast<std::int32_t>(C::PathLine));
  EXPECT_FALSE(r.board->path().active());
}

TEST(BoardPath, AStopBrakesAlongThePathAndSaysStopped) {
  PathRig p;
  p.r.send(C::PathLine, 150000, C::PathLine, 50000);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  for (int k = 0; k < 15; ++k) {
    p.r.send(C::Nop, 0, C::Nop, 0);
    p.tick(100);
  }
  ASSERT_TRUE(p.r.board->path().active());
  p.r.send(C::Stop, 0, C::Nop, 0);
  p.tick();
  EXPECT_TRUE(p.r.board->path().stopping());
  p.run_until_idle();
  EXPECT_LT(p.um(Axis::X), 150000);
  EXPECT_EQ(p.r.board->axis_event(Axis::X), AxisEvent::StoppedByUser);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, ALostLinkStopsThePath) {
  PathRig p;
  p.r.send(C::PathLine, 150000, C::PathLine, 0);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(6000);  // silence: the watchdog expires after three command periods (docs/motion.md §7)
  EXPECT_FALSE(p.r.board->path().active());
  EXPECT_LT(p.um(Axis::X), 150000);
  EXPECT_EQ(p.r.board->axis_event(Axis::X), AxisEvent::LinkLost);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, TheAxesOwnCommandsAreRefusedWhileAPathRuns) {
  PathRig p;
  p.r.send(C::PathLine, 100000, C::PathLine, 0);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(2);
  p.r.send(C::Nop, 0, C::Nop, 0);
  p.tick(100);
  p.r.send(C::Goto, 5000, C::Jog, 1);
  p.tick();
  const auto e = p.r.last_echo();
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->x.status, S::CommandRefused);
  EXPECT_EQ(e->x.data, static_cast<std::int32_t>(C::Goto));
  EXPECT_EQ(e->y.status, S::CommandRefused);
  p.r.send(C::SetFastSpeed, 2000, C::Nop, 0);  // not below the homing speed (docs/storage.md)
  p.tick();
  EXPECT_EQ(p.r.last_echo()->x.status, S::CommandRefused);
  p.run_until_idle();
  EXPECT_EQ(p.um(Axis::X), 100000);
}

TEST(BoardPath, AnEndstopHaltsThePathAndSaysEndstop) {
  PathRig p;
  p.r.send(C::PathLine, 100000, C::PathLine, 0);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  for (int k = 0; k < 5; ++k) {
    p.r.send(C::Nop, 0, C::Nop, 0);
    p.tick(100);
  }
  p.r.in.endstop_max[0] = 1;
  p.tick();
  EXPECT_FALSE(p.r.board->path().active());
  EXPECT_EQ(p.r.board->axis_event(Axis::X), AxisEvent::Endstop);
  EXPECT_EQ(p.r.board->motor_output(Axis::X).steps, 0);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, TheThesisMachineHalfCircleKeepsEveryAxisProperty) {
  // Full steps (20 steps/mm): the minor axis's first step at the top of an arc comes when it
  // already moves at a few % of the path speed, above the start speed (10 steps/s): DIR must
  // turn with the speed, not with that step (docs/cnc.md "Axis speeds").
  PathRig p;
  p.r.send(C::SetPitch, 10000, C::Nop, 0);
  p.r.send(C::SetMicrosteps, 1, C::Nop, 0);
  p.r.send(C::SetFastSpeed, 50000, C::Nop, 0);
  p.r.send(C::SetAccel, 40000, C::Nop, 0);
  p.tick(5);  // one new frame per tick (docs/protocol.md "Two frames in one cycle")
  p.r.send(C::PathLine, 100000, C::PathLine, 150000);
  p.r.send(C::PathCentre, 100000, C::PathCentre, 100000);
  p.r.send(C::PathArcCw, 100000, C::PathArcCw, 50000);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(5);
  p.run_until_idle();
  EXPECT_EQ(p.um(Axis::X), 100000);
  EXPECT_EQ(p.um(Axis::Y), 50000);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, ABlockOnAnArcBrakesAlongThePathAndStaysStopped) {
  // USB plugged mid-arc (seed-000's block): a controlled stop along the arc, where one axis's
  // share of the speed passes zero and rises again while the path brakes; once at rest, not one
  // step until unblocked (docs/cnc.md "Stops", models/xy/safety).
  PathRig p;
  p.r.send(C::PathLine, 50000, C::PathLine, 100000);
  p.r.send(C::PathCentre, 50000, C::PathCentre, 50000);
  p.r.send(C::PathArcCw, 50000, C::PathArcCw, 0);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(2);
  bool on_arc = false;
  for (int t = 0; t < 40000 && !on_arc; t += 100) {
    p.r.send(C::Nop, 0, C::Nop, 0);
    p.tick(100);
    on_arc = p.um(Axis::X) > 60000;
  }
  ASSERT_TRUE(on_arc);
  p.r.in.usb = true;
  for (int t = 0; t < 5000; t += 100) {
    p.r.send(C::Nop, 0, C::Nop, 0);
    p.tick(100);
  }
  EXPECT_FALSE(p.r.board->path().active());
  const std::int32_t x = p.um(Axis::X);
  p.tick(500);
  EXPECT_EQ(p.um(Axis::X), x);
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

TEST(BoardPath, StepPulsesAddUpToTheCounterOnTinyCircles) {
  // Fine mechanics (0.2 mm/rev, 256 microsteps: 256 usteps/um) make the thesis's jerk large in
  // microsteps, so ten tangent circles of 1 um (256 usteps) run at about 35 moves per tick
  // (the centripetal cap sqrt(a r / 2)) and each axis reverses inside a tick: the STEP pulses of a tick share one DIR, so every pulse must still
  // count (docs/cnc.md "Reversal inside a tick").
  PathRig p;
  // Speeds first: each set must convert within the axis ranges (<= 1e6 usteps/s, 1e7 usteps/s^2).
  p.r.send(C::SetSlowSpeed, 500, C::Nop, 0);
  p.r.send(C::SetFastSpeed, 2000, C::Nop, 0);  // not below the homing speed (docs/storage.md)
  p.r.send(C::SetAccel, 38000, C::Nop, 0);  // 9.7e6 usteps/s^2: the arc cap sqrt(a r / 2) is ~35 moves per tick
  p.r.send(C::SetPitch, 200, C::Nop, 0);
  p.r.send(C::SetMicrosteps, 256, C::Nop, 0);
  p.tick(6);  // one new frame per tick (docs/protocol.md "Two frames in one cycle")
  ASSERT_EQ(p.r.board->mechanics().microsteps, 256);
  ASSERT_EQ(p.r.board->mechanics().pitch_um, 200);
  p.r.send(C::PathLine, 1000, C::PathLine, 1000);
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  p.tick(2);
  p.run_until_idle();
  ASSERT_EQ(p.r.ax(Axis::X).pos, 256000);
  p.r.steps_total = {p.r.ax(Axis::X).pos, p.r.ax(Axis::Y).pos};
  // Centre 1 um to the right; ten full circles (end = start), all tangent: one chain.
  for (int k = 0; k < 10; ++k) {
    p.r.send(C::PathCentre, 1001, C::PathCentre, 1000);
    p.r.send(C::PathArcCcw, 1000, C::PathArcCcw, 1000);
    p.tick(2);  // the board takes one new frame per tick (docs/protocol.md "Two frames in one cycle")
  }
  p.r.send(C::PathEnd, 0, C::Nop, 0);
  int max_steps = 0;
  for (int t = 0; t < 3000; ++t) {
    if (t % 100 == 0) p.r.send(C::Nop, 0, C::Nop, 0);
    p.tick();
    max_steps = std::max(max_steps, p.r.board->motor_output(Axis::X).steps);
    ASSERT_EQ(p.r.steps_total[0], p.r.ax(Axis::X).pos) << "tick " << t;
    ASSERT_EQ(p.r.steps_total[1], p.r.ax(Axis::Y).pos) << "tick " << t;
  }
  EXPECT_FALSE(p.r.board->path().active());
  EXPECT_EQ(p.r.ax(Axis::X).pos, 256000);
  EXPECT_GE(max_steps, 25);  // many moves per tick: reversals inside a tick do happen
  EXPECT_TRUE(p.violations.empty()) << p.violations.front().what;
}

}  // namespace
