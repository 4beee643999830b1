// The board's half of delivery (docs/protocol.md "Delivery"): a frame runs only when its seq is
// newer than the last one taken (1..499 ahead, mod 1000); a repeat is answered with the same
// outcome and feeds the link watchdog; an older frame is answered with the last seq taken.
#include <gtest/gtest.h>

#include "sim/xy/rig/board_rig.hpp"
#include "protocol/xy/codec/statuses.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;
using C = xy_codec::CommandId;
using S = xy_codec::EchoStatus;

namespace {

// A board at rest, homed by its encoders at 10 mm on both axes (2 mm lead, 200 steps, 16
// microsteps: 3200 usteps per rev, so 5 revolutions).
// (The rig is built in place: the board holds a pointer to it.)
void boot_homed(Rig& r) {
  r.in.encoder[0] = {5, 0, 1};
  r.in.encoder[1] = {5, 0, 1};
  r.boot();
}

void send_seq(Rig& r, std::uint16_t seq, C x, std::int32_t xd, C y = C::Nop, std::int32_t yd = 0) {
  r.send_raw(Rig::bytes_of(Rig::frame_of(seq, x, xd, y, yd)));
}

xy_frame::EchoFrame last(const Rig& r) {
  const auto e = r.last_echo();
  EXPECT_TRUE(e.has_value());
  return e.value_or(xy_frame::EchoFrame{});
}

}  // namespace

TEST(BoardDelivery, ARepeatedRelativeMoveRunsOnceAndItsRepeatIsAnswered) {
  Rig r;
  boot_homed(r);
  const std::int32_t start = r.ax(Axis::X).pos;
  send_seq(r, 40, C::Move, 1000);  // +1 mm = 1600 usteps
  r.tick();
  EXPECT_EQ(r.ax(Axis::X).target, start + 1600);
  send_seq(r, 40, C::Move, 1000);
  r.tick();
  EXPECT_EQ(r.ax(Axis::X).target, start + 1600) << "a repeat must not move again";
  EXPECT_EQ(r.board->counters().repeated_frames, 1U);
  EXPECT_EQ(r.board->counters().dispatched_frames, 1U);
  ASSERT_EQ(r.tx.size(), 2U);
  EXPECT_EQ(last(r).seq, 40);
  r.tick(3000);
  EXPECT_EQ(r.ax(Axis::X).pos, start + 1600);
}

TEST(BoardDelivery, AnOlderFrameDoesNotRunAndIsAnsweredWithTheLastSeqTaken) {
  Rig r;
  boot_homed(r);
  send_seq(r, 41, C::Goto, 12000);
  r.tick();
  const std::int32_t target = r.ax(Axis::X).target;
  send_seq(r, 40, C::Goto, 15000);
  r.tick();
  EXPECT_EQ(r.ax(Axis::X).target, target);
  EXPECT_EQ(last(r).seq, 41);
  EXPECT_EQ(r.board->counters().older_frames, 1U);
  // 500 ahead is as far as "older" goes (half the seq space).
  send_seq(r, 541, C::Goto, 15000);
  r.tick();
  EXPECT_EQ(r.ax(Axis::X).target, target);
  EXPECT_EQ(r.board->counters().older_frames, 2U);
  // 499 ahead is new.
  send_seq(r, 540, C::Goto, 15000);
  r.tick();
  EXPECT_NE(r.ax(Axis::X).target, target);
  EXPECT_EQ(last(r).seq, 540);
}

TEST(BoardDelivery, TheSeqWrapsFrom999To0) {
  Rig r;
  boot_homed(r);
  send_seq(r, 998, C::Nop, 0);
  r.tick();
  send_seq(r, 999, C::Nop, 0);
  r.tick();
  send_seq(r, 0, C::Move, 1000);
  r.tick();
  EXPECT_EQ(last(r).seq, 0);
  EXPECT_EQ(r.board->counters().dispatched_frames, 3U);
  send_seq(r, 999, C::Move, 1000);  // late copy from before the wrap
  r.tick();
  EXPECT_EQ(r.board->counters().dispatched_frames, 3U);
  EXPECT_EQ(last(r).seq, 0);
}

TEST(BoardDelivery, AnyFirstSeqAfterPowerUpIsNew) {
  for (const std::uint16_t seq : {std::uint16_t{0}, std::uint16_t{1}, std::uint16_t{500}, std::uint16_t{999}}) {
    Rig r;
  boot_homed(r);
    send_seq(r, seq, C::Move, 1000);
    r.tick();
    EXPECT_EQ(r.board->counters().dispatched_frames, 1U) << seq;
    EXPECT_EQ(last(r).seq, seq);
  }
}

TEST(BoardDelivery, TheAnswerToARepeatTellsTheSameRefusalAsTheFirstAnswer) {
  Rig r;
  boot_homed(r);
  send_seq(r, 7, C::Goto, 999999, C::Move, 1000);  // beyond the soft limit: refused
  r.tick();
  const xy_frame::EchoFrame first = last(r);
  EXPECT_EQ(first.x.status, S::CommandRefused);
  EXPECT_EQ(first.x.data, static_cast<std::int32_t>(C::Goto));
  r.tick(50);
  send_seq(r, 7, C::Goto, 999999, C::Move, 1000);
  r.tick();
  const xy_frame::EchoFrame again = last(r);
  EXPECT_EQ(again.seq, 7);
  EXPECT_EQ(again.x.status, S::CommandRefused);
  EXPECT_EQ(again.x.data, static_cast<std::int32_t>(C::Goto));
  EXPECT_NE(again.y.status, S::CommandRefused);
  // A new frame clears it.
  send_seq(r, 8, C::Nop, 0);
  r.tick();
  EXPECT_NE(last(r).x.status, S::CommandRefused);
}

TEST(BoardDelivery, TheAnswerToARepeatOfABlockedFrameSaysBlockedAfterTheBlockEnds) {
  Rig r;
  boot_homed(r);
  r.in.charger = true;
  r.tick();
  send_seq(r, 3, C::Move, 1000);
  r.tick();
  EXPECT_EQ(last(r).x.status, S::BlockedCharger);
  r.in.charger = false;
  r.tick();
  send_seq(r, 3, C::Move, 1000);
  r.tick();
  EXPECT_EQ(last(r).x.status, S::BlockedCharger) << "the repeat tells what happened to the frame";
  EXPECT_EQ(r.ax(Axis::X).mode, xy_axis::Mode::Idle);
}

TEST(BoardDelivery, RepeatsFeedTheLinkWatchdogOlderFramesDoNot) {
  Rig r;
  boot_homed(r);
  send_seq(r, 10, C::Jog, 1);
  r.tick();
  for (int t = 0; t < 2000; ++t) {
    if (t % 100 == 0) send_seq(r, 10, C::Jog, 1);  // the client repeating an unanswered frame
    r.tick();
  }
  EXPECT_EQ(r.ax(Axis::X).mode, xy_axis::Mode::Jog);
  EXPECT_EQ(r.board->counters().watchdog_expiries, 0U);
  for (int t = 0; t < 2000; ++t) {
    if (t % 100 == 0) send_seq(r, 9, C::Jog, 1);   // older: proves nothing about the PC now
    r.tick();
  }
  EXPECT_EQ(r.board->counters().watchdog_expiries, 1U);
  EXPECT_NE(r.ax(Axis::X).mode, xy_axis::Mode::Jog);
}

// docs/protocol.md "Delivery": the answer to a repeat tells the outcome its frame had when it
// was taken. A move that ran, with the board blocked afterwards (each cause of §7.5.2), is
// answered with the state now and no BLOCKED_*: the client reads BLOCKED_* as "did not take
// effect", and a user told so would send the relative move again and move twice.
TEST(BoardDelivery, TheAnswerToARepeatOfAFrameThatRanDoesNotShowALaterBlock) {
  for (int cause = 0; cause < 3; ++cause) {
    SCOPED_TRACE(cause == 0 ? "usb" : cause == 1 ? "charger" : "battery");
    Rig r;
    boot_homed(r);
    const std::int32_t start = r.ax(Axis::X).pos;
    send_seq(r, 5, C::Move, 1000);
    r.tick();
    EXPECT_EQ(r.ax(Axis::X).target, start + 1600);
    r.tick(100);
    EXPECT_NE(r.ax(Axis::X).pos, start) << "the move ran";
    if (cause == 0) r.in.usb = true;
    if (cause == 1) r.in.charger = true;
    if (cause == 2) r.in.battery_mv = 3000;  // below the 3300 mV default (docs/storage.md)
    r.tick();
    send_seq(r, 5, C::Move, 1000);
    r.tick();
    const xy_frame::EchoFrame again = last(r);
    EXPECT_EQ(again.seq, 5);
    EXPECT_NE(again.x.status, S::BlockedUsb);
    EXPECT_NE(again.x.status, S::BlockedCharger);
    EXPECT_NE(again.x.status, S::BlockedBattery);
    EXPECT_NE(again.x.status, S::CommandRefused);
    // A new frame taken now is blocked, and says so.
    send_seq(r, 6, C::Nop, 0);
    r.tick();
    EXPECT_EQ(last(r).x.status, cause == 0 ? S::BlockedUsb : cause == 1 ? S::BlockedCharger : S::BlockedBattery);
  }
}

// docs/board.md "Echo content": the answer to a frame tells a refusal of its command before a
// standing fault, or a refused goto would be reported done. A sensor fault (the temperature
// sensor lost) does not stop motion (docs/sensors.md), so motion commands still run or are
// refused beside it.
TEST(BoardDelivery, ARefusalShowsBeforeAStandingFault) {
  Rig r;
  r.tmp117.present = false;  // configure fails: the temperature sensor is lost at boot
  boot_homed(r);
  send_seq(r, 1, C::Nop, 0);
  r.tick();
  ASSERT_EQ(last(r).x.status, S::Fault) << "precondition: a standing fault";
  send_seq(r, 2, C::Goto, 999999);  // beyond the soft limit: refused
  r.tick();
  EXPECT_EQ(last(r).x.status, S::CommandRefused);
  EXPECT_EQ(last(r).x.data, static_cast<std::int32_t>(C::Goto));
  EXPECT_EQ(last(r).y.status, S::Fault) << "the fault shows where nothing was refused";
}
