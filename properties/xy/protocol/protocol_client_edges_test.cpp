// PC client edges: every rejection of the readable command form names the problem and leaves
// the output frame unchanged; frames outside the wire ranges are not formatted (and use no
// seq); a rejection in the Y half of an echo is found; rejection codes this client does not
// know are shown as '?' rather than read out of the table.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "pc/xy/client/readable.hpp"
#include "core/xy/frame/echo_builder.hpp"
#include "core/xy/frame/echo_codec.hpp"

namespace {

namespace f = ap::xy_frame;
namespace c = ap::xy_codec;
using ap::xy_client::EchoKind;

TEST(ProtocolClientEdges, ReadableRejectionsNameTheProblem) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"hello", "expected key=value, got 'hello'"},
      {"x=goto:", "bad number ''"},
      {"x=goto:+", "bad number '+'"},
      {"x=goto:abc", "bad number 'abc'"},
      {"x=goto:1:2", "too many ':' in 'goto:1:2'"},
      {"y=jog:+:medium", "jog speed must be fast or slow"},
      {"y=jog:up:fast", "jog direction must be + or -"},
      {"x=goto:1000000", "goto data 1000000 outside [0, 999999]"},
      {"sub=humidity", "unknown subscriber 'humidity'"},
      {"sub=encoder:y", "bad argument 'y'"},
      {"sub=encoder:1:2", "too many ':' in 'encoder:1:2'"},
      {"sub=encoder:2", "encoder argument 2 out of range"},
      {"seq=abc", "seq must be 0..999"},
      {"seq=-1", "seq must be 0..999"},
      {"seq=1000", "seq must be 0..999"},
      {"speed=5", "unknown key 'speed' (x, y, sub, seq)"},
  };
  f::CommandFrame fr;
  ASSERT_EQ(ap::xy_client::parse_readable("seq=7 x=move:-5", fr), "");
  const f::CommandFrame before = fr;
  for (const auto& [text, message] : cases) {
    EXPECT_EQ(ap::xy_client::parse_readable(text, fr), message) << text;
    EXPECT_EQ(fr, before) << text;
  }
}

TEST(ProtocolClientEdges, ReadableAcceptsSignsAndAllForms) {
  f::CommandFrame fr;
  ASSERT_EQ(ap::xy_client::parse_readable("seq=+999 x=goto:+20 y=jog:-:slow sub=encoder:+1 sub=param:5", fr), "");
  EXPECT_EQ(fr.seq, 999);
  EXPECT_EQ(fr.x, (f::AxisCommand{c::CommandId::Goto, 20}));
  EXPECT_EQ(fr.y, (f::AxisCommand{c::CommandId::Jog, -c::kJogSlow}));
  EXPECT_EQ(fr.subs[0], (f::SubscriberSlot{c::SubscriberId::EncoderUm, 1}));
  EXPECT_EQ(fr.subs[1], (f::SubscriberSlot{c::SubscriberId::Param, 5}));
  f::CommandFrame again;
  ASSERT_EQ(ap::xy_client::parse_readable(ap::xy_client::to_readable(fr), again), "");
  EXPECT_EQ(again, fr);
  // The readable form names the subscriber slots it fills and skips the empty ones.
  EXPECT_EQ(ap::xy_client::to_readable(fr), "seq=999 x=goto:20 y=jog:-1 sub=encoder:1 sub=param:5");
}

TEST(ProtocolClientEdges, OutOfRangeFramesAreNotFormattedAndUseNoSeq) {
  f::CommandFrame bad_cmd;
  bad_cmd.x = {c::CommandId::Goto, -1};   // goto is 0..999999
  EXPECT_EQ(ap::xy_client::format(bad_cmd), std::nullopt);
  f::CommandFrame bad_seq;
  bad_seq.seq = 1000;
  EXPECT_EQ(ap::xy_client::format(bad_seq), std::nullopt);

  f::EchoFrame bad_echo;
  bad_echo.x = {c::EchoStatus::FrameRejected, 100000};   // reason*100 + offset is 0..99999
  EXPECT_EQ(ap::xy_client::format(bad_echo), std::nullopt);

  ap::xy_client::Client cl;
  ASSERT_TRUE(cl.poll(0, {}).has_value());   // a keep-alive takes seq 0
  const auto counters = cl.counters();
  cl.submit({ap::xy_client::Part::X, bad_cmd.x}, 0);
  EXPECT_EQ(cl.next_seq(), 1) << "a refused command consumes no seq";
  EXPECT_EQ(cl.counters().sent, counters.sent);
  EXPECT_EQ(cl.queued(), 0U);
}

TEST(ProtocolClientEdges, RejectionInTheYHalfIsFound) {
  ap::xy_client::Client cl;
  ASSERT_TRUE(cl.poll(0, {}).has_value());
  f::EchoFrame e;
  e.seq = 0;
  e.x = {c::EchoStatus::Idle, 0};
  e.y = {c::EchoStatus::FrameRejected, f::rejection_code({c::FrameError::DataOutOfRange, 17})};
  const auto ev = cl.receive(*ap::xy_client::format(e), 0);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, EchoKind::Rejected);
  EXPECT_EQ(ev[0].rejection, (f::Rejection{c::FrameError::DataOutOfRange, 17}));
  EXPECT_EQ(cl.counters().rejected, 1U);
}

TEST(ProtocolClientEdges, UnknownRejectionReasonsAreShownAsUnknown) {
  const f::Rejection known{c::FrameError::BadCrc, 36};
  EXPECT_EQ(ap::xy_client::describe(known), "bad_crc at byte 36 (CRC-16 does not match the payload)");
  // A board with a newer error table: reason 99 is not ours.
  const f::Rejection unknown = f::rejection_from_code(99 * c::kRejectReasonScale + 5);
  EXPECT_EQ(unknown.offset, 5);
  EXPECT_EQ(ap::xy_client::describe(unknown), "? at byte 5");
  EXPECT_EQ(c::error_key(unknown.error), "?");

  f::EchoFrame e;
  e.x = {c::EchoStatus::FrameRejected, f::rejection_code(known)};
  e.y = {c::EchoStatus::Idle, 0};
  const std::string text = ap::xy_client::describe(e);
  EXPECT_NE(text.find("[bad_crc at byte 36"), std::string::npos) << text;
}

// The echo side of the codec at its edges: a seq outside 0..999 is refused at the seq field;
// a buffer longer than an echo is BadLength at the first byte past the frame (shorter: at its
// end); a negative reason code (not produced by a board) decodes to "no rejection".
TEST(ProtocolClientEdges, EchoCodecEdges) {
  f::EchoFrame e;
  e.seq = c::kSeqModulo;
  EXPECT_EQ(f::validate(e), (f::Rejection{c::FrameError::DataOutOfRange, static_cast<std::uint16_t>(c::kSeqOffset)}));
  EXPECT_EQ(ap::xy_client::format(e), std::nullopt);
  e.seq = c::kSeqModulo - 1;
  const std::string good = *ap::xy_client::format(e);
  ASSERT_EQ(good.size(), c::kEchoLength);

  const f::EchoFrame sentinel{7, {c::EchoStatus::Homing, 1}, {c::EchoStatus::Idle, 2}, {}};
  f::EchoFrame out = sentinel;
  const std::string longer = good + "0";
  const auto as_bytes = [](const std::string& s) {
    return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  };
  EXPECT_EQ(f::parse_echo(as_bytes(longer), out),
            (f::Rejection{c::FrameError::BadLength, static_cast<std::uint16_t>(c::kEchoLength)}));
  EXPECT_EQ(out, sentinel);
  const std::string shorter = good.substr(0, good.size() - 3);
  EXPECT_EQ(f::parse_echo(as_bytes(shorter), out),
            (f::Rejection{c::FrameError::BadLength, static_cast<std::uint16_t>(shorter.size())}));
  EXPECT_EQ(out, sentinel);
  ASSERT_TRUE(f::parse_echo(as_bytes(good), out).ok());
  EXPECT_EQ(out, e);

  EXPECT_EQ(f::rejection_from_code(-1), (f::Rejection{c::FrameError::None, 0}));
  EXPECT_TRUE(f::rejection_from_code(-1).ok());
}

}  // namespace
