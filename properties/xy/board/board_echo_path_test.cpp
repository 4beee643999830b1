// The coordinated path (docs/cnc.md "On the board") against the echo reference model
// (models/xy/echo, docs/echo-model.md "The coordinated path"): a real core/xy/board is driven with
// path frames (lines, arcs, every refusal the model decides, a stop mid-path, an endstop, a
// lost link) and the model checks EVERY echo; each scenario also states, typed in from
// docs/cnc.md, the statuses the PC must see at its key points. A deliberately wrong echo must
// be caught (the check can fail).
//
// Set-up (docs/board.md "Step counter and boot", eq. 7-2, 2 mm lead): X homed at 50 000 um,
// Y at 101 000 um; defaults: 1600 usteps/mm, soft limits 0 .. 200 000 um, fast 10 mm/s.
// Runs are a few mm long (each <= ~1 s of simulated time); the whole binary stays well under
// 1 s (measured in docs/echo-model.md).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "sim/xy/rig/board_rig.hpp"
#include "sim/xy/rig/rig_sensors.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "models/xy/echo/board_checker.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/statuses.hpp"

using namespace ap;
using ap::sim::xy::Rig;
using xy_codec::CommandId;
using xy_codec::EchoStatus;
namespace em = ap::model::xy_echo;

namespace {

constexpr int kKeepAlive = 100;  // the PC repeats a frame every 100 ms (docs/protocol.md)

struct PathBench {
  Rig rig;
  std::unique_ptr<em::BoardChecker> checker;
  std::vector<std::string> bad;
  std::size_t checked = 0;
  xy_frame::EchoFrame last{};  // the board's last echo, parsed

  explicit PathBench(bool homed = true) {
    if (homed) {
      rig.in.encoder[0] = {25, 0, 1};     // 25 turns  = 50 000 um
      rig.in.encoder[1] = {50, 8192, 1};  // 50.5 turns = 101 000 um
    }
    rig.boot();
    checker = std::make_unique<em::BoardChecker>(*rig.board, ap::sim::xy::boot_facts_of(rig));
  }

  // One tick, its echoes checked by the model (or replaced by `forge` to test the check).
  void tick(bool forge = false) {
    const std::size_t before = rig.tx.size();
    rig.tick();
    std::vector<em::EchoBytes> sent(rig.tx.begin() + static_cast<std::ptrdiff_t>(before), rig.tx.end());
    if (!sent.empty()) (void)xy_frame::parse_echo(sent.back(), last);
    if (forge && !sent.empty()) {
      xy_frame::EchoFrame e = last;
      e.x.status = EchoStatus::TargetReached;  // a wrong status the model must catch
      (void)xy_frame::format_echo(e, sent.back());
    }
    checked += sent.size();
    for (auto& m : checker->after_tick(sent, ap::sim::xy::sensors_of(rig))) bad.push_back(m);
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }
  void send(CommandId x, std::int32_t xd, CommandId y = CommandId::Nop, std::int32_t yd = 0, bool forge = false) {
    const auto b = Rig::bytes_of(Rig::frame_of(++rig.seq, x, xd, y, yd));
    rig.send_raw(b);
    checker->rx(b);
    tick(forge);
  }
  // Runs with the PC's keep-alive frames until the path is at rest (or `max` ticks).
  int run_to_rest(int max = 3000) {
    int t = 0;
    while (rig.board->path().active() && t < max) {
      if (t % kKeepAlive == kKeepAlive - 1) {
        send(CommandId::Nop, 0);
      } else {
        tick();
      }
      ++t;
    }
    return t;
  }
  void nop() { send(CommandId::Nop, 0); }
  std::string report() const {
    std::string s;
    for (const auto& m : bad) s += m + "\n";
    return s;
  }
};

bool refused(const xy_frame::AxisEcho& e, CommandId id) {
  return e.status == EchoStatus::CommandRefused && e.data == static_cast<std::int32_t>(id);
}

}  // namespace

// A line, then path_end: both axes REACHED at its end (cnc.md "Stops": at the end of the last
// chain both axes say reached), positions in um exactly the line's end.
TEST(EchoModelPath, LineReachesItsEnd) {
  PathBench b;
  b.send(CommandId::PathLine, 52000, CommandId::PathLine, 103000);
  EXPECT_EQ(b.last.x.status, EchoStatus::Idle);  // queued, the chain not closed yet
  b.send(CommandId::PathEnd, 0);
  EXPECT_GT(b.run_to_rest(), 0);
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.y.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.x.data, 52000);
  EXPECT_EQ(b.last.y.data, 103000);
  // The next line starts a new motion: the event that ended the last one is gone (IDLE).
  b.send(CommandId::PathLine, 50000, CommandId::PathLine, 101000);
  EXPECT_EQ(b.last.x.status, EchoStatus::Idle);
  EXPECT_EQ(b.last.y.status, EchoStatus::Idle);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// A quarter arc, counter-clockwise: start (50, 101) mm, centre (50, 103) mm, end (52, 103).
TEST(EchoModelPath, ArcReachesItsEnd) {
  PathBench b;
  b.send(CommandId::PathCentre, 50000, CommandId::PathCentre, 103000);
  b.send(CommandId::PathArcCcw, 52000, CommandId::PathArcCcw, 103000);
  b.send(CommandId::PathEnd, 0);
  bool moved = false;
  for (int i = 0; i < 50; ++i) {
    b.tick();
    moved |= b.rig.ax(xy_board::Axis::X).phase != xy_axis::Phase::Stop;
  }
  b.nop();
  EXPECT_TRUE(moved);
  b.run_to_rest();
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.y.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.x.data, 52000);
  EXPECT_EQ(b.last.y.data, 103000);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// A clockwise arc after a line (a chain of two segments) and an X-only line.
TEST(EchoModelPath, ChainOfLineArcAndSingleAxisLine) {
  PathBench b;
  b.send(CommandId::PathLine, 51000, CommandId::Nop, 0);  // X only: Y keeps 101 000
  b.send(CommandId::PathCentre, 51000, CommandId::PathCentre, 100000);
  b.send(CommandId::PathArcCw, 52000, CommandId::PathArcCw, 100000);
  b.send(CommandId::PathEnd, 0);
  b.run_to_rest();
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.y.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.x.data, 52000);
  EXPECT_EQ(b.last.y.data, 100000);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// Each refusal cause the model decides (cnc.md "Refusals"): COMMAND_REFUSED with the ID on
// each part carrying a path command, and nothing changes (the next valid line still runs).
TEST(EchoModelPath, RefusalsCarryTheCommandId) {
  {
    PathBench u(false);  // not homed
    u.send(CommandId::PathLine, 1000, CommandId::PathLine, 1000);
    EXPECT_TRUE(refused(u.last.x, CommandId::PathLine));
    EXPECT_TRUE(refused(u.last.y, CommandId::PathLine));
    EXPECT_TRUE(u.bad.empty()) << u.report();
  }
  PathBench b;
  // Mixed parts: a centre and a segment; a line and an arc; a centre in one part only.
  b.send(CommandId::PathCentre, 0, CommandId::PathLine, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathCentre));
  EXPECT_TRUE(refused(b.last.y, CommandId::PathLine));
  b.send(CommandId::Nop, 0, CommandId::PathCentre, 103000);
  EXPECT_TRUE(refused(b.last.y, CommandId::PathCentre));
  b.send(CommandId::PathLine, 52000, CommandId::PathArcCw, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathLine));
  EXPECT_TRUE(refused(b.last.y, CommandId::PathArcCw));
  // An arc with no centre.
  b.send(CommandId::PathArcCw, 52000, CommandId::PathArcCw, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathArcCw));
  // A line to where the axes stand: zero length (only the X part carries it).
  b.send(CommandId::PathLine, 50000, CommandId::Nop, 0);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathLine));
  EXPECT_EQ(b.last.y.status, EchoStatus::Idle);
  // An end outside the soft limits (0 .. 200 000 um).
  b.send(CommandId::Nop, 0, CommandId::PathLine, 200001);
  EXPECT_TRUE(refused(b.last.y, CommandId::PathLine));
  // Zero radius: the centre is the start.
  b.send(CommandId::PathCentre, 50000, CommandId::PathCentre, 101000);
  EXPECT_EQ(b.last.x.status, EchoStatus::Idle);  // a centre alone is stored
  b.send(CommandId::PathArcCcw, 52000, CommandId::PathArcCcw, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathArcCcw));
  // Radius mismatch: start radius 2 mm, end radius 2.1 mm (> max(2 steps, 0.1 %)).
  b.send(CommandId::PathCentre, 50000, CommandId::PathCentre, 103000);
  b.send(CommandId::PathArcCcw, 52100, CommandId::PathArcCcw, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathArcCcw));
  EXPECT_TRUE(refused(b.last.y, CommandId::PathArcCcw));
  // A swept extreme outside: centre (20, 101) mm, r = 30 mm, ccw from 0 to 270 deg passes
  // 180 deg at x = -10 mm although both ends are inside.
  b.send(CommandId::PathCentre, 20000, CommandId::PathCentre, 101000);
  b.send(CommandId::PathArcCcw, 20000, CommandId::PathArcCcw, 71000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathArcCcw));
  // The same arc clockwise (0 to 270 deg the short way) passes only 270 deg: accepted.
  b.send(CommandId::PathArcCw, 20000, CommandId::PathArcCw, 71000);
  EXPECT_EQ(b.last.x.status, EchoStatus::Idle);
  b.send(CommandId::Stop, 0);  // drop it again
  b.run_to_rest();
  // Busy: an axis jogging on its own; then sleeping.
  b.send(CommandId::Jog, 1);
  b.ticks(5);
  b.send(CommandId::PathLine, 52000, CommandId::PathLine, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathLine));
  b.send(CommandId::Stop, 0);
  b.ticks(200);
  b.send(CommandId::PeriphOff, 0);
  b.send(CommandId::PathLine, 52000, CommandId::PathLine, 103000);
  EXPECT_TRUE(refused(b.last.y, CommandId::PathLine));
  b.send(CommandId::PeriphOn, 0);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// 16 segments queued and not finished: the 17th is refused (QueueFull).
TEST(EchoModelPath, SeventeenthSegmentIsRefused) {
  PathBench b;
  for (int k = 0; k < 16; ++k) {
    // A zigzag of 10 mm lines: every junction is a corner, the first chain takes ~1 s.
    b.send(CommandId::PathLine, 50000 + 10000 * ((k + 1) % 2), CommandId::PathLine, 101000 + 1000 * (k + 1));
    EXPECT_NE(b.last.x.status, EchoStatus::CommandRefused) << k;
  }
  b.send(CommandId::PathLine, 70000, CommandId::PathLine, 150000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathLine));
  EXPECT_TRUE(refused(b.last.y, CommandId::PathLine));
  b.send(CommandId::Stop, 0);
  b.run_to_rest();
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// Mid-path: motion commands and parameters other than the currents are refused; irun is
// taken; a stop brakes along the path, a segment sent while it stops is refused (Stopping),
// and both axes end STOPPED.
TEST(EchoModelPath, StopMidPath) {
  PathBench b;
  b.send(CommandId::PathLine, 56000, CommandId::PathLine, 105000);
  b.send(CommandId::PathEnd, 0);
  b.ticks(150);
  b.send(CommandId::Goto, 1000, CommandId::Jog, 1);
  EXPECT_TRUE(refused(b.last.x, CommandId::Goto));
  EXPECT_TRUE(refused(b.last.y, CommandId::Jog));
  b.send(CommandId::Home, 0, CommandId::SetAccel, 5000);
  EXPECT_TRUE(refused(b.last.x, CommandId::Home));
  EXPECT_TRUE(refused(b.last.y, CommandId::SetAccel));
  b.send(CommandId::SetIrun, 20);
  EXPECT_NE(b.last.x.status, EchoStatus::CommandRefused);
  b.send(CommandId::Nop, 0, CommandId::Stop, 0);
  b.send(CommandId::PathLine, 52000, CommandId::PathLine, 103000);
  EXPECT_TRUE(refused(b.last.x, CommandId::PathLine));
  b.run_to_rest();
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::StoppedByUser);
  EXPECT_EQ(b.last.y.status, EchoStatus::StoppedByUser);
  EXPECT_LT(b.last.x.data, 56000);  // stopped short of the end
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// Sleep stops the path as `stop` does (docs/cnc.md "Stops"): a path that has not moved yet
// (waiting for `path_end`) drops its queue at once, in the handler, so a parameter later in
// the same frame finds no path and is taken (docs/echo-model.md "The coordinated path").
// Found by BoardEchoModel.EveryEchoMatchesTheModel (RC seed 444): the board refused it.
TEST(EchoModelPath, SleepDropsAStandingPathAtOnce) {
  PathBench b;
  b.send(CommandId::SetIrun, 0, CommandId::PathLine, 0);
  ASSERT_TRUE(b.rig.board->path().active());
  b.send(CommandId::PeriphOff, 0, CommandId::SetSlowSpeed, 500);
  EXPECT_FALSE(b.rig.board->path().active());
  EXPECT_EQ(b.last.x.status, EchoStatus::Sleeping);
  EXPECT_EQ(b.last.y.status, EchoStatus::Sleeping);
  EXPECT_EQ(b.rig.board->store().current().slow_speed_um_s, 500U);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// An endstop toward which an axis steps halts the path: both axes ENDSTOP.
TEST(EchoModelPath, EndstopHaltsThePath) {
  PathBench b;
  b.send(CommandId::PathLine, 56000, CommandId::PathLine, 104000);
  b.send(CommandId::PathEnd, 0);
  b.ticks(150);
  b.rig.in.endstop_max[0] = 1;
  b.ticks(2);
  b.rig.in.endstop_max[0] = 0;
  b.run_to_rest();
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::EndstopHit);
  EXPECT_EQ(b.last.y.status, EchoStatus::EndstopHit);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// No frame for 300 ticks during a path: a controlled stop, both axes LINK_LOST.
TEST(EchoModelPath, LostLinkStopsThePath) {
  PathBench b;
  // A line never closed (no path_end) waits; the lost link drops it with nothing ended.
  b.send(CommandId::PathLine, 52000, CommandId::PathLine, 103000);
  b.ticks(400);
  EXPECT_FALSE(b.rig.board->path().active());
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::Idle);
  EXPECT_EQ(b.last.x.data, 50000);
  b.send(CommandId::PathLine, 58000, CommandId::PathLine, 101000);
  b.send(CommandId::PathEnd, 0);
  b.ticks(2000);
  EXPECT_FALSE(b.rig.board->path().active());
  b.nop();
  EXPECT_EQ(b.last.x.status, EchoStatus::LinkLost);
  EXPECT_EQ(b.last.y.status, EchoStatus::LinkLost);
  EXPECT_LT(b.last.x.data, 58000);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// A goto stored earlier in the same frame is superseded by the segment (docs/echo-model.md
// "The coordinated path"): no refusal, the path runs, the goto never does.
TEST(EchoModelPath, ASegmentBesideAMotionCommandIsRefusedAsMixed) {
  // docs/cnc.md "Refusals": the segment is refused (MixedParts), the goto runs as it would alone.
  PathBench b;
  b.send(CommandId::Goto, 1000, CommandId::PathLine, 103000);
  EXPECT_NE(b.last.x.status, EchoStatus::CommandRefused);
  EXPECT_EQ(b.last.y.status, EchoStatus::CommandRefused);
  EXPECT_EQ(b.last.y.data, static_cast<std::int32_t>(CommandId::PathLine));
  for (int k = 0; k < 80; ++k) {  // the goto runs alone: 49 mm at the default 10 mm/s
    b.nop();
    b.ticks(99);
  }
  EXPECT_EQ(b.last.x.status, EchoStatus::TargetReached);
  EXPECT_EQ(b.last.x.data, 1000);
  EXPECT_TRUE(b.bad.empty()) << b.report();
}

// The check can fail: the echo of an accepted line, forged to say REACHED for X, is caught.
TEST(EchoModelPath, WrongEchoIsCaught) {
  PathBench b;
  b.send(CommandId::PathLine, 52000, CommandId::PathLine, 103000, /*forge=*/true);
  ASSERT_EQ(b.bad.size(), 1U);
  EXPECT_NE(b.bad[0].find("model expects idle"), std::string::npos) << b.bad[0];
}
