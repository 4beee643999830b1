// PC client: delivery (docs/protocol.md "Delivery": one frame in flight, repeated until
// answered, stop first, outcomes, the retry budget, renumbering) and the readable form used by
// `axisproof frame encode`.
#include <gtest/gtest.h>

#include <string>

#include "pc/xy/client/client.hpp"
#include "pc/xy/client/readable.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_builder.hpp"

namespace {

namespace f = ap::xy_frame;
namespace c = ap::xy_codec;
using ap::xy_client::EchoKind;

using ap::xy_client::Client;
using ap::xy_client::Command;
using ap::xy_client::Outcome;
using ap::xy_client::Part;
using C = c::CommandId;
using S = c::EchoStatus;

std::string echo_for(std::uint16_t seq, S x = S::Idle, std::int32_t xd = 10, S y = S::Idle, std::int32_t yd = 20) {
  return *ap::xy_client::format(f::EchoFrame{seq, {x, xd}, {y, yd}, {}});
}

f::CommandFrame parsed(const std::string& bytes) {
  f::CommandFrame fr;
  EXPECT_TRUE(f::parse_command(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), fr).ok());
  return fr;
}

constexpr std::int64_t ms = 1000;

// docs/protocol.md "Delivery": 1..499 ahead is new, 0 ahead a repeat, 500..999 ahead older,
// all mod 1000 (the values below are the document's, not the code's constants).
TEST(ProtocolDelivery, SeqWindowAsDocumented) {
  EXPECT_EQ(c::seq_order(5, 6), c::SeqOrder::New);
  EXPECT_EQ(c::seq_order(5, 5), c::SeqOrder::Repeat);
  EXPECT_EQ(c::seq_order(5, 4), c::SeqOrder::Older);
  EXPECT_EQ(c::seq_order(999, 0), c::SeqOrder::New);     // the wrap
  EXPECT_EQ(c::seq_order(998, 3), c::SeqOrder::New);
  EXPECT_EQ(c::seq_order(0, 999), c::SeqOrder::Older);
  EXPECT_EQ(c::seq_order(3, 998), c::SeqOrder::Older);
  EXPECT_EQ(c::seq_order(0, 499), c::SeqOrder::New);
  EXPECT_EQ(c::seq_order(0, 500), c::SeqOrder::Older);   // half the space: never both new and older
  EXPECT_EQ(c::seq_order(600, 99), c::SeqOrder::New);
  EXPECT_EQ(c::seq_order(600, 100), c::SeqOrder::Older);
  EXPECT_EQ(c::seq_next(999), 0);
}

TEST(ProtocolDelivery, AFrameIsRepeatedByteForByteUntilItsAnswer) {
  Client cl;
  cl.submit({Part::X, {C::Goto, 20000}}, 0);
  const auto first = cl.poll(0, {});
  ASSERT_TRUE(first);
  EXPECT_EQ(parsed(*first).x, (f::AxisCommand{C::Goto, 20000}));
  EXPECT_EQ(parsed(*first).seq, 0);
  EXPECT_FALSE(cl.poll(39 * ms, {}));            // the 40 ms retransmission timeout
  const auto again = cl.poll(40 * ms, {});
  ASSERT_TRUE(again);
  EXPECT_EQ(*again, *first);
  EXPECT_TRUE(cl.take_reports().empty());
  const auto ev = cl.receive(echo_for(0, S::Accelerating), 55 * ms);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, ap::xy_client::EchoKind::Answer);
  const auto reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 1U);
  EXPECT_EQ(reps[0].outcome, Outcome::Done);
  EXPECT_EQ(reps[0].transmissions, 2U);
  EXPECT_EQ(reps[0].settled_us, 55 * ms);
  EXPECT_EQ(cl.counters().retransmissions, 1U);
  EXPECT_TRUE(cl.idle());
}

TEST(ProtocolDelivery, TheNextFrameWaitsForTheAnswerOfTheOneInFlight) {
  Client cl;
  cl.submit({Part::X, {C::Goto, 1000}}, 0);
  cl.submit({Part::X, {C::Move, 500}}, 0);
  const auto a = cl.poll(0, {});
  ASSERT_TRUE(a);
  const auto b = cl.poll(40 * ms, {});
  ASSERT_TRUE(b);
  EXPECT_EQ(*a, *b);                              // not the move: the goto is unanswered
  cl.receive(echo_for(0), 45 * ms);
  const auto n = cl.poll(45 * ms, {});
  ASSERT_TRUE(n);
  EXPECT_EQ(parsed(*n).seq, 1);
  EXPECT_EQ(parsed(*n).x, (f::AxisCommand{C::Move, 500}));
}

TEST(ProtocolDelivery, ARejectionEchoIsNeverAnAnswerAndTriggersARepeatAtOnce) {
  Client cl({.first_seq = 7});
  cl.submit({Part::X, {C::Move, 500}}, 0);
  ASSERT_TRUE(cl.poll(0, {}));
  // The board's rejection carries the last seq it took: here even the frame's own.
  for (const std::uint16_t seq : {std::uint16_t{6}, std::uint16_t{7}}) {
    const auto rej = *ap::xy_client::format(f::build_rejection_echo(seq, {c::FrameError::BadCrc, 36}));
    const auto ev = cl.receive(rej, 5 * ms);
    ASSERT_EQ(ev.size(), 1U);
    EXPECT_EQ(ev[0].kind, ap::xy_client::EchoKind::Rejected);
    EXPECT_TRUE(cl.take_reports().empty());
    EXPECT_TRUE(cl.poll(5 * ms, {}));              // sent again without waiting for the timeout
  }
  EXPECT_EQ(cl.counters().rejected, 2U);
  EXPECT_FALSE(cl.idle());
}

TEST(ProtocolDelivery, AStopJumpsTheQueueAndCancelsTheEarlierMotionOfItsAxis) {
  Client cl;
  cl.submit({Part::X, {C::Goto, 1000}}, 0);
  ASSERT_TRUE(cl.poll(0, {}));                    // in flight: left alone
  const auto g2 = cl.submit({Part::X, {C::Goto, 9000}}, 1);
  const auto mv = cl.submit({Part::X, {C::Move, 100}}, 2);
  cl.submit({Part::Unit, {C::SetAccel, 30000}}, 3);
  cl.submit({Part::Y, {C::Goto, 5000}}, 4);
  cl.submit({Part::X, {C::Stop, 0}}, 5);
  auto reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 2U);
  EXPECT_EQ(reps[0].ticket, g2);
  EXPECT_EQ(reps[0].outcome, Outcome::Superseded);
  EXPECT_EQ(reps[1].ticket, mv);
  EXPECT_EQ(reps[1].outcome, Outcome::Superseded);
  EXPECT_FALSE(cl.poll(10 * ms, {}));             // the stop waits for the frame in flight ...
  cl.receive(echo_for(0), 10 * ms);
  const auto n = cl.poll(10 * ms, {});             // ... and goes in the very next one
  ASSERT_TRUE(n);
  EXPECT_EQ(parsed(*n).x, (f::AxisCommand{C::Stop, 0}));
  EXPECT_EQ(parsed(*n).y, (f::AxisCommand{C::SetAccel, 30000}));  // behind it, in order
  cl.receive(echo_for(1), 20 * ms);
  const auto last = cl.poll(20 * ms, {});
  ASSERT_TRUE(last);
  EXPECT_EQ(parsed(*last).y, (f::AxisCommand{C::Goto, 5000}));
}

TEST(ProtocolDelivery, PacksAnXCommandWithTheNextYOrUnitCommandButNeverYBeforeX) {
  Client cl;
  cl.submit({Part::Y, {C::Goto, 1}}, 0);
  cl.submit({Part::X, {C::Goto, 2}}, 0);
  auto fr = parsed(*cl.poll(0, {}));
  EXPECT_EQ(fr.y, (f::AxisCommand{C::Goto, 1}));
  EXPECT_EQ(fr.x, (f::AxisCommand{}));            // X runs first on the board: not packed
  cl.receive(echo_for(0), 1);
  fr = parsed(*cl.poll(1, {}));
  EXPECT_EQ(fr.x, (f::AxisCommand{C::Goto, 2}));
}

TEST(ProtocolDelivery, OutcomesComeFromTheStatusOfTheCommandsPart) {
  Client cl;
  cl.submit({Part::X, {C::Goto, 1000}}, 0);
  cl.submit({Part::Y, {C::Home, 0}}, 0);
  ASSERT_TRUE(cl.poll(0, {}));
  cl.receive(echo_for(0, S::CommandRefused, static_cast<std::int32_t>(C::Goto), S::Homing, 0), 10 * ms);
  auto reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 2U);
  EXPECT_EQ(reps[0].outcome, Outcome::Refused);
  EXPECT_EQ(reps[1].outcome, Outcome::Done);
  cl.submit({Part::X, {C::Goto, 1000}}, 20 * ms);
  ASSERT_TRUE(cl.poll(20 * ms, {}));
  cl.receive(echo_for(1, S::BlockedCharger, 0, S::BlockedCharger, 0), 30 * ms);
  reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 1U);
  EXPECT_EQ(reps[0].outcome, Outcome::Blocked);
  EXPECT_FALSE(ap::xy_client::delivered(Outcome::Superseded));
  EXPECT_TRUE(ap::xy_client::delivered(Outcome::Blocked));
}

TEST(ProtocolDelivery, GivesUpAfterTheBudgetThenFailsCommandsUntilAProbeIsAnswered) {
  Client cl({.retransmit_us = 40 * ms, .max_transmissions = 3, .keepalive_us = 100 * ms, .first_seq = 0});
  cl.submit({Part::X, {C::Move, 500}}, 0);
  cl.submit({Part::Y, {C::Move, 500}}, 0);  // packed with it
  cl.submit({Part::X, {C::Goto, 9}}, 0);    // waits behind
  for (const std::int64_t t : {0, 40, 80}) ASSERT_TRUE(cl.poll(t * ms, {})) << t;
  EXPECT_FALSE(cl.link_down());
  const auto probe = cl.poll(120 * ms, {});   // out of transmissions: given up, a probe goes out
  ASSERT_TRUE(probe);
  EXPECT_TRUE(cl.link_down());
  EXPECT_EQ(parsed(*probe).seq, 1);           // the given-up seq is never reused
  auto reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 3U);
  EXPECT_EQ(reps[0].outcome, Outcome::Unconfirmed);
  EXPECT_EQ(reps[1].outcome, Outcome::Unconfirmed);
  EXPECT_EQ(reps[2].outcome, Outcome::LinkDown);
  cl.submit({Part::X, {C::Stop, 0}}, 130 * ms);
  reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 1U);
  EXPECT_EQ(reps[0].outcome, Outcome::LinkDown);
  cl.receive(echo_for(1), 150 * ms);
  EXPECT_FALSE(cl.link_down());
  cl.submit({Part::X, {C::Stop, 0}}, 160 * ms);
  EXPECT_TRUE(cl.take_reports().empty());
  EXPECT_EQ(cl.counters().given_up, 1U);
}

TEST(ProtocolDelivery, RenumbersTheFrameInFlightWhenTheBoardIsAhead) {
  Client cl;
  cl.submit({Part::X, {C::Move, 500}}, 0);
  ASSERT_TRUE(cl.poll(0, {}));
  // A board that took seq 200 from another sender answers our 0 as older, with its 200.
  auto ev = cl.receive(echo_for(200), 5 * ms);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, ap::xy_client::EchoKind::Resync);
  const auto again = cl.poll(5 * ms, {});
  ASSERT_TRUE(again);
  EXPECT_EQ(parsed(*again).seq, 201);
  EXPECT_EQ(parsed(*again).x, (f::AxisCommand{C::Move, 500}));
  // An echo of an earlier frame is late, not a reason to renumber.
  ev = cl.receive(echo_for(199), 6 * ms);
  EXPECT_EQ(ev[0].kind, ap::xy_client::EchoKind::Late);
  cl.receive(echo_for(201), 7 * ms);
  ASSERT_EQ(cl.take_reports().size(), 1U);
  EXPECT_EQ(cl.counters().resyncs, 1U);
}

TEST(ProtocolDelivery, AKeepAliveEveryPeriodWhenIdleCarryingTheHeldJog) {
  Client cl({.first_seq = 998});
  ap::xy_client::Extras ex;
  ex.jog = {2, 0};
  const auto k0 = cl.poll(0, ex);
  ASSERT_TRUE(k0);
  EXPECT_EQ(parsed(*k0).x, (f::AxisCommand{C::Jog, 2}));
  EXPECT_EQ(parsed(*k0).y, (f::AxisCommand{}));
  cl.receive(echo_for(998), 10 * ms);
  EXPECT_FALSE(cl.poll(99 * ms, ex));
  const auto k1 = cl.poll(100 * ms, ex);
  ASSERT_TRUE(k1);
  EXPECT_EQ(parsed(*k1).seq, 999);
  cl.receive(echo_for(999), 110 * ms);
  EXPECT_EQ(parsed(*cl.poll(200 * ms, ex)).seq, 0);   // the wrap
  EXPECT_TRUE(cl.take_reports().empty());             // keep-alives are not user commands
}

TEST(ProtocolDelivery, ACommandOutsideTheTablesIsInvalidAndTakesNoSeq) {
  Client cl;
  cl.submit({Part::X, {C::Goto, -5}}, 0);
  const auto reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 1U);
  EXPECT_EQ(reps[0].outcome, Outcome::Invalid);
  EXPECT_EQ(cl.queued(), 0U);
  EXPECT_EQ(cl.next_seq(), 0);
}

// docs/storage.md "Factory and user parameters" (thesis §7.5.4): the operator's client sends
// speeds and acceleration; the machine's parameters (pitch, steps, microsteps, currents) only
// from a client opened for factory work.
TEST(ProtocolDelivery, FactoryParametersNeedAFactoryClient) {
  for (const C id : {C::SetPitch, C::SetSteps, C::SetMicrosteps, C::SetIrun, C::SetIhold}) {
    Client cl;
    cl.submit({Part::X, {id, 16}}, 0);
    const auto reps = cl.take_reports();
    ASSERT_EQ(reps.size(), 1U);
    EXPECT_EQ(reps[0].outcome, Outcome::Invalid) << c::info(id).key;
    EXPECT_EQ(cl.queued(), 0U);
  }
  for (const C id : {C::SetAccel, C::SetFastSpeed, C::SetSlowSpeed, C::SetStartSpeed}) {
    Client cl;
    cl.submit({Part::X, {id, 5000}}, 0);
    EXPECT_TRUE(cl.take_reports().empty()) << c::info(id).key;
    EXPECT_EQ(cl.queued(), 1U) << c::info(id).key;
  }
  ap::xy_client::Config factory;
  factory.factory = true;
  Client cl(factory);
  cl.submit({Part::X, {C::SetPitch, 4000}}, 0);
  EXPECT_TRUE(cl.take_reports().empty());
  EXPECT_EQ(cl.queued(), 1U);
}

TEST(ProtocolReadable, ParsesTheIssueExampleAndRejectsNonsense) {
  f::CommandFrame fr;
  ASSERT_EQ(ap::xy_client::parse_readable("x=jog:+:fast y=goto:20000 sub=battery", fr), "");
  EXPECT_EQ(fr.x, (f::AxisCommand{c::CommandId::Jog, 2}));
  EXPECT_EQ(fr.y, (f::AxisCommand{c::CommandId::Goto, 20000}));
  EXPECT_EQ(fr.subs[0], (f::SubscriberSlot{c::SubscriberId::BatteryMv, 0}));
  f::CommandFrame again;
  ASSERT_EQ(ap::xy_client::parse_readable(ap::xy_client::to_readable(fr), again), "");
  EXPECT_EQ(again, fr);
  const f::CommandFrame before = fr;
  for (const char* bad : {"x=fly", "x=goto:-5", "x=jog:*:fast", "sub=encoder:3", "seq=1000", "z=nop", "x=goto:12a",
                          "sub=battery sub=battery sub=battery sub=battery sub=battery"}) {
    EXPECT_NE(ap::xy_client::parse_readable(bad, fr), "") << bad;
    EXPECT_EQ(fr, before) << bad;
  }
}

}  // namespace

namespace {

TEST(ProtocolDelivery, ASecondStopOfAnAxisWhileItsFirstIsQueuedRidesWithIt) {
  Client cl;
  cl.submit({Part::Y, {C::Goto, 1000}}, 0);
  ASSERT_TRUE(cl.poll(0, {}));
  const auto s1 = cl.submit({Part::X, {C::Stop, 0}}, 1);
  const auto g = cl.submit({Part::X, {C::Goto, 5000}}, 2);
  const auto s2 = cl.submit({Part::X, {C::Stop, 0}}, 3);   // cancels the goto issued before it
  auto reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 1U);
  EXPECT_EQ(reps[0].ticket, g);
  EXPECT_EQ(reps[0].outcome, Outcome::Superseded);
  EXPECT_EQ(cl.queued(), 1U);
  cl.receive(echo_for(0), 10 * ms);
  EXPECT_EQ(cl.take_reports().size(), 1U);   // the Y goto
  const auto n = cl.poll(10 * ms, {});
  ASSERT_TRUE(n);
  EXPECT_EQ(parsed(*n).x, (f::AxisCommand{C::Stop, 0}));
  cl.receive(echo_for(1, S::Decelerating), 20 * ms);
  reps = cl.take_reports();
  ASSERT_EQ(reps.size(), 2U);
  EXPECT_EQ(reps[0].ticket, s1);
  EXPECT_EQ(reps[1].ticket, s2);
  EXPECT_EQ(reps[1].issued_us, 3);
  EXPECT_EQ(reps[1].seq, reps[0].seq);
  EXPECT_EQ(cl.counters().delivered, 3U);
  EXPECT_TRUE(cl.idle());
}

TEST(ProtocolDelivery, StopsOfBothAxesShareOneFrameWhicheverCameFirst) {
  Client cl;
  cl.submit({Part::X, {C::Goto, 1000}}, 0);
  ASSERT_TRUE(cl.poll(0, {}));
  cl.submit({Part::Y, {C::Stop, 0}}, 1);
  cl.submit({Part::X, {C::Stop, 0}}, 2);
  cl.receive(echo_for(0), 10 * ms);
  const auto fr = parsed(*cl.poll(10 * ms, {}));
  EXPECT_EQ(fr.x, (f::AxisCommand{C::Stop, 0}));
  EXPECT_EQ(fr.y, (f::AxisCommand{C::Stop, 0}));
}

}  // namespace
