// PC client: sequence numbers, lost / duplicated / rejected / unexpected echoes, and the
// readable form used by `axisproof frame encode`.
#include <gtest/gtest.h>

#include <string>

#include "client/client.hpp"
#include "client/readable.hpp"
#include "core/frame/echo_builder.hpp"

namespace {

namespace f = ap::frame;
namespace c = ap::codec;
using ap::client::EchoKind;

std::string echo_for(std::uint16_t seq) {
  return *ap::client::format(f::EchoFrame{seq, {c::EchoStatus::Idle, 10}, {c::EchoStatus::Idle, 20}, {}});
}

TEST(ProtocolClient, NumbersCommandsAndWrapsAt1000) {
  ap::client::Client cl;
  for (int i = 0; i < 1001; ++i) ASSERT_TRUE(cl.next_command({}).has_value());
  EXPECT_EQ(cl.next_seq(), 1);
  EXPECT_EQ(cl.counters().sent, 1001U);
  EXPECT_EQ(cl.in_flight().size(), ap::client::Client::kMaxInFlight);
  EXPECT_EQ(cl.counters().lost, 1001U - ap::client::Client::kMaxInFlight);
}

TEST(ProtocolClient, DetectsLostDuplicatedRejectedUnexpectedAndMalformed) {
  ap::client::Client cl;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(cl.next_command({}).has_value());  // seqs 0..4
  auto ev = cl.receive(echo_for(0) + echo_for(2) + echo_for(2) + echo_for(500));
  ASSERT_EQ(ev.size(), 4U);
  EXPECT_EQ(ev[0].kind, EchoKind::Matched);
  EXPECT_TRUE(ev[0].lost.empty());
  EXPECT_EQ(ev[1].kind, EchoKind::Matched);
  EXPECT_EQ(ev[1].lost, (std::vector<std::uint16_t>{1}));
  EXPECT_EQ(ev[2].kind, EchoKind::Duplicate);
  EXPECT_EQ(ev[3].kind, EchoKind::Unexpected);
  std::string corrupt = echo_for(3);
  corrupt[10] = '7';
  const auto rejected = *ap::client::format(f::build_rejection_echo(2, {c::FrameError::BadCrc, 36}));
  ev = cl.receive(corrupt + rejected);
  ASSERT_EQ(ev.size(), 2U);
  EXPECT_EQ(ev[0].kind, EchoKind::Malformed);
  EXPECT_EQ(ev[0].rejection.error, c::FrameError::BadCrc);
  EXPECT_EQ(ev[1].kind, EchoKind::Rejected);
  EXPECT_EQ(ev[1].rejection, (f::Rejection{c::FrameError::BadCrc, 36}));
  ev = cl.receive(echo_for(4));
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].lost, (std::vector<std::uint16_t>{3}));
  const auto& n = cl.counters();
  EXPECT_EQ(n.matched, 3U);
  EXPECT_EQ(n.lost, 2U);
  EXPECT_EQ(n.duplicated, 1U);
  EXPECT_EQ(n.unexpected, 1U);
  EXPECT_EQ(n.rejected, 1U);
  EXPECT_EQ(n.malformed, 1U);
  EXPECT_TRUE(cl.in_flight().empty());
}

TEST(ProtocolReadable, ParsesTheIssueExampleAndRejectsNonsense) {
  f::CommandFrame fr;
  ASSERT_EQ(ap::client::parse_readable("x=jog:+:fast y=goto:20000 sub=battery", fr), "");
  EXPECT_EQ(fr.x, (f::AxisCommand{c::CommandId::Jog, 2}));
  EXPECT_EQ(fr.y, (f::AxisCommand{c::CommandId::Goto, 20000}));
  EXPECT_EQ(fr.subs[0], (f::SubscriberSlot{c::SubscriberId::BatteryMv, 0}));
  f::CommandFrame again;
  ASSERT_EQ(ap::client::parse_readable(ap::client::to_readable(fr), again), "");
  EXPECT_EQ(again, fr);
  const f::CommandFrame before = fr;
  for (const char* bad : {"x=fly", "x=goto:-5", "x=jog:*:fast", "sub=encoder:3", "seq=1000", "z=nop", "x=goto:12a",
                          "sub=battery sub=battery sub=battery sub=battery sub=battery"}) {
    EXPECT_NE(ap::client::parse_readable(bad, fr), "") << bad;
    EXPECT_EQ(fr, before) << bad;
  }
}

}  // namespace
