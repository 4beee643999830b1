// Callback table, dispatch, echo builder, command link, and the doc tables.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "pc/xy/client/doc_tables.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "core/xy/frame/callback_table.hpp"
#include "core/xy/frame/echo_builder.hpp"

namespace {

namespace f = ap::xy_frame;
namespace c = ap::xy_codec;

struct Call {
  int handler;
  f::Axis axis;
  std::int32_t data;
  bool operator==(const Call&) const = default;
};

struct Recorder {
  std::vector<Call> calls;
};

template <int N>
f::HandlerStatus record(void* ctx, f::Axis axis, std::int32_t data) {
  static_cast<Recorder*>(ctx)->calls.push_back({N, axis, data});
  return f::HandlerStatus::Done;
}

f::CallbackTable full_table() {
  f::CallbackTable t;
  for (std::uint32_t id = 0; id < f::CallbackTable::kSize; ++id) EXPECT_TRUE(t.install(id, &record<0>));
  return t;
}

TEST(ProtocolCallbackTable, BoundsAreCheckedOnInstallAndLookup) {
  f::CallbackTable t;
  EXPECT_TRUE(t.install(f::CallbackTable::kSize - 1, &record<1>));
  EXPECT_FALSE(t.install(f::CallbackTable::kSize, &record<1>));
  EXPECT_FALSE(t.install(255, &record<1>));
  EXPECT_EQ(t.find(f::CallbackTable::kSize - 1), &record<1>);
  EXPECT_EQ(t.find(f::CallbackTable::kSize), nullptr);
  EXPECT_EQ(t.find(0xFFFFFFFFU), nullptr);
  EXPECT_EQ(t.find(0), nullptr);
}

TEST(ProtocolCallbackTable, DispatchCallsOneHandlerPerAxisInOrder) {
  f::CallbackTable t;
  ASSERT_TRUE(t.install(c::CommandId::Stop, &record<1>));
  ASSERT_TRUE(t.install(c::CommandId::Goto, &record<3>));
  Recorder rec;
  const f::CommandFrame fr{1, {c::CommandId::Stop, 0}, {c::CommandId::Goto, 20000}, {}};
  const auto r = t.dispatch(fr, &rec);
  EXPECT_TRUE(r.rejection.ok());
  EXPECT_EQ(rec.calls, (std::vector<Call>{{1, f::Axis::X, 0}, {3, f::Axis::Y, 20000}}));
}

TEST(ProtocolCallbackTable, MissingHandlerRejectsTheWholeFrame) {
  f::CallbackTable t;
  ASSERT_TRUE(t.install(c::CommandId::Stop, &record<1>));
  Recorder rec;
  const auto r = t.dispatch({1, {c::CommandId::Stop, 0}, {c::CommandId::Goto, 5}, {}}, &rec);
  EXPECT_EQ(r.rejection, (f::Rejection{c::FrameError::Unhandled, 12}));
  EXPECT_TRUE(rec.calls.empty());
}

TEST(ProtocolCallbackTable, HandMadeFramesOutsideTheTableAreRejected) {
  const auto t = full_table();
  Recorder rec;
  f::CommandFrame fr;
  fr.y.id = static_cast<c::CommandId>(c::kCommandCount);
  EXPECT_EQ(t.dispatch(fr, &rec).rejection, (f::Rejection{c::FrameError::UnknownCommand, 12}));
  fr.y = {c::CommandId::Goto, -1};
  EXPECT_EQ(t.dispatch(fr, &rec).rejection, (f::Rejection{c::FrameError::DataOutOfRange, 14}));
  EXPECT_TRUE(rec.calls.empty());
}

f::AxisEcho absurd_axis(void*, f::Axis a) {
  return a == f::Axis::X ? f::AxisEcho{c::EchoStatus::ConstantSpeed, 5'000'000} : f::AxisEcho{static_cast<c::EchoStatus>(77), 1};
}
std::int32_t absurd_sub(void*, f::SubscriberSlot) { return -5'000'000; }

TEST(ProtocolEchoBuilder, ClampsBoardValuesSoTheEchoAlwaysFormats) {
  f::SubscriberSlots req{};
  req[1] = {c::SubscriberId::BatteryMv, 0};
  req[2] = {c::SubscriberId::ChargeMa, 0};
  const auto e = f::build_echo(1234, req, {nullptr, &absurd_axis, &absurd_sub});
  EXPECT_EQ(e.seq, 234);
  EXPECT_EQ(e.x, (f::AxisEcho{c::EchoStatus::ConstantSpeed, 999999}));
  EXPECT_EQ(e.y, (f::AxisEcho{c::EchoStatus::Fault, 0}));
  EXPECT_EQ(e.subs[0], (f::SubscriberPacket{}));
  EXPECT_EQ(e.subs[1], (f::SubscriberPacket{req[1], 0}));
  EXPECT_EQ(e.subs[2], (f::SubscriberPacket{req[2], -99999}));
  EXPECT_TRUE(ap::xy_client::format(e).has_value());
}

TEST(ProtocolEchoBuilder, RejectionEchoCarriesReasonAndOffset) {
  const auto e = f::build_rejection_echo(42, {c::FrameError::BadCrc, 36});
  EXPECT_EQ(e.seq, 42);
  EXPECT_EQ(e.x, (f::AxisEcho{c::EchoStatus::FrameRejected, 436}));
  EXPECT_EQ(e.y, e.x);
  EXPECT_EQ(f::rejection_from_code(436), (f::Rejection{c::FrameError::BadCrc, 36}));
  EXPECT_EQ(ap::xy_client::format(e).value_or(""), "<042140004361400043600000000000000000000000000000000000000009C77;");
}

// Every line of the generated tables must appear verbatim in docs/protocol.md, so the doc
// cannot drift from protocol/codec.
TEST(ProtocolDocs, TablesInDocsMatchTheCodecTables) {
  std::ifstream in(std::string(AP_SOURCE_DIR) + "/docs/protocol.md");
  ASSERT_TRUE(in.good());
  std::stringstream doc;
  doc << in.rdbuf();
  std::istringstream lines(ap::xy_client::all_tables_md());
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    EXPECT_NE(doc.str().find(line + "\n"), std::string::npos) << "docs/protocol.md lacks: " << line;
    ++count;
  }
  EXPECT_GT(count, 50);
}

}  // namespace
