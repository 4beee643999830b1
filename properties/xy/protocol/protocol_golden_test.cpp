// Golden vectors (protocol/xy/vectors/golden.json, written by an independent Python renderer):
// every valid frame decodes to its expected fields and formats back to its exact bytes;
// every invalid frame gets its expected typed error at its expected offset.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "pc/xy/client/readable.hpp"
#include "protocol/xy/codec/crc16.hpp"
#include "protocol/xy/codec/errors.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/frame/stream_framer.hpp"

namespace {

using nlohmann::json;
namespace f = ap::xy_frame;
namespace c = ap::xy_codec;

const json& vectors() {
  static const json j = [] {
    std::ifstream in(std::string(AP_SOURCE_DIR) + "/protocol/xy/vectors/golden.json");
    return json::parse(in);
  }();
  return j;
}

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

c::FrameError error_named(const std::string& key) {
  for (const auto& e : c::kFrameErrors) {
    if (e.key == key) return e.error;
  }
  ADD_FAILURE() << "unknown error key " << key;
  return c::FrameError::None;
}

f::CommandFrame expected_command(const json& e) {
  f::CommandFrame fr;
  fr.seq = e["seq"].get<std::uint16_t>();
  fr.x = {static_cast<c::CommandId>(e["x"][0].get<int>()), e["x"][1].get<std::int32_t>()};
  fr.y = {static_cast<c::CommandId>(e["y"][0].get<int>()), e["y"][1].get<std::int32_t>()};
  for (std::size_t i = 0; i < fr.subs.size(); ++i) {
    fr.subs[i] = {static_cast<c::SubscriberId>(e["subs"][i][0].get<int>()), e["subs"][i][1].get<std::uint8_t>()};
  }
  return fr;
}

f::EchoFrame expected_echo(const json& e) {
  f::EchoFrame fr;
  fr.seq = e["seq"].get<std::uint16_t>();
  fr.x = {static_cast<c::EchoStatus>(e["x"][0].get<int>()), e["x"][1].get<std::int32_t>()};
  fr.y = {static_cast<c::EchoStatus>(e["y"][0].get<int>()), e["y"][1].get<std::int32_t>()};
  for (std::size_t i = 0; i < fr.subs.size(); ++i) {
    const auto& p = e["subs"][i];
    fr.subs[i] = {{static_cast<c::SubscriberId>(p[0].get<int>()), p[1].get<std::uint8_t>()}, p[2].get<std::int32_t>()};
  }
  return fr;
}

TEST(ProtocolGolden, Crc16CcittFalseCheckValues) {
  constexpr std::array<std::uint8_t, 9> kCheckInput{'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  // 0x29B1: CRC-16/CCITT-FALSE's published check value over "123456789" (docs/protocol.md),
  // stated here rather than read from the codec's own constant.
  static_assert(c::crc16(kCheckInput) == 0x29B1);
  ASSERT_FALSE(vectors()["crc16_ccitt_false"].empty());
  for (const auto& v : vectors()["crc16_ccitt_false"]) {
    const auto in = v["input"].get<std::string>();
    EXPECT_EQ(c::crc16(bytes_of(in)), std::stoul(v["crc"].get<std::string>(), nullptr, 16)) << in;
  }
}

TEST(ProtocolGolden, ValidCommandsDecodeAndFormatBack) {
  ASSERT_GE(vectors()["commands"].size(), 5U);
  for (const auto& v : vectors()["commands"]) {
    SCOPED_TRACE(v["name"].get<std::string>());
    const auto bytes = v["bytes"].get<std::string>();
    const auto want = expected_command(v["expect"]);
    f::CommandFrame got;
    const auto r = f::parse_command(bytes_of(bytes), got);
    EXPECT_TRUE(r.ok()) << c::error_key(r.error) << " at " << r.offset;
    EXPECT_EQ(got, want);
    EXPECT_EQ(ap::xy_client::format(want).value_or("(rejected)"), bytes);
    f::CommandFrame from_text;
    EXPECT_EQ(ap::xy_client::parse_readable(v["readable"].get<std::string>(), from_text), "");
    EXPECT_EQ(from_text, want);
  }
}

TEST(ProtocolGolden, InvalidCommandsGetTheirTypedErrorAndChangeNothing) {
  ASSERT_GE(vectors()["invalid_commands"].size(), 10U);
  for (const auto& v : vectors()["invalid_commands"]) {
    SCOPED_TRACE(v["name"].get<std::string>());
    const auto bytes = v["bytes"].get<std::string>();
    f::CommandFrame out;
    out.seq = 777;
    const f::CommandFrame before = out;
    const auto r = f::parse_command(bytes_of(bytes), out);
    EXPECT_EQ(c::error_key(r.error), v["error"].get<std::string>());
    EXPECT_EQ(r.offset, v["offset"].get<int>());
    EXPECT_EQ(out, before);
  }
}

TEST(ProtocolGolden, EchoesDecodeAndFormatBack) {
  for (const auto& v : vectors()["echoes"]) {
    SCOPED_TRACE(v["name"].get<std::string>());
    const auto bytes = v["bytes"].get<std::string>();
    const auto want = expected_echo(v["expect"]);
    f::EchoFrame got;
    EXPECT_TRUE(f::parse_echo(bytes_of(bytes), got).ok());
    EXPECT_EQ(got, want);
    EXPECT_EQ(ap::xy_client::format(want).value_or("(rejected)"), bytes);
  }
  for (const auto& v : vectors()["invalid_echoes"]) {
    SCOPED_TRACE(v["name"].get<std::string>());
    f::EchoFrame out;
    const auto r = f::parse_echo(bytes_of(v["bytes"].get<std::string>()), out);
    EXPECT_EQ(r.error, error_named(v["error"].get<std::string>()));
    EXPECT_EQ(r.offset, v["offset"].get<int>());
  }
}

TEST(ProtocolGolden, StreamsFrameAsExpected) {
  ASSERT_GE(vectors()["command_streams"].size(), 4U);
  for (const auto& v : vectors()["command_streams"]) {
    SCOPED_TRACE(v["name"].get<std::string>());
    f::CommandFramer framer;
    std::vector<f::CommandFramer::Event> events;
    framer.feed(bytes_of(v["bytes"].get<std::string>()), [&](const auto& e) { events.push_back(e); });
    ASSERT_EQ(events.size(), v["events"].size());
    for (std::size_t i = 0; i < events.size(); ++i) {
      const auto& want = v["events"][i];
      EXPECT_EQ(events[i].stream_offset, want["offset"].get<std::uint32_t>()) << i;
      EXPECT_EQ(c::error_key(events[i].rejection.error), want["error"].get<std::string>()) << i;
      if (want.contains("at")) {
        EXPECT_EQ(events[i].rejection.offset, want["at"].get<int>()) << i;
      }
    }
    EXPECT_EQ(framer.counters().rejected_bytes, v["rejected_bytes"].get<std::uint32_t>());
  }
}

// The CRC alone detects every 1- and 2-bit error in its payload; this checks the whole
// frame, CRC characters included, exhaustively for golden frames of both kinds.
template <class Frame, class Parse>
void expect_every_double_bit_error_rejected(const std::string& good, Parse parse) {
  const std::size_t bits = good.size() * 8;
  std::size_t checked = 0;
  for (std::size_t i = 0; i < bits; ++i) {
    for (std::size_t j = i; j < bits; ++j) {
      std::string bad = good;
      bad[i / 8] = static_cast<char>(bad[i / 8] ^ (1 << (i % 8)));
      if (j != i) bad[j / 8] = static_cast<char>(bad[j / 8] ^ (1 << (j % 8)));
      Frame out;
      ASSERT_FALSE(parse(bytes_of(bad), out).ok()) << "bits " << i << "," << j << ": " << bad;
      ++checked;
    }
  }
  EXPECT_EQ(checked, bits * (bits + 1) / 2);
}

TEST(ProtocolGolden, EveryDoubleBitErrorInGoldenFramesIsRejected) {
  for (const auto& v : vectors()["commands"]) {
    expect_every_double_bit_error_rejected<f::CommandFrame>(v["bytes"].get<std::string>(), f::parse_command);
  }
  expect_every_double_bit_error_rejected<f::EchoFrame>(vectors()["echoes"][3]["bytes"].get<std::string>(), f::parse_echo);
}

}  // namespace
