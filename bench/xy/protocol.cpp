// Protocol throughput: parse (incl. CRC) and format per frame, and the stream framer over a
// capture-like stream. Reported as frames per second ("frames/s" counter).
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "protocol/xy/codec/crc16.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/frame/stream_framer.hpp"

namespace {

namespace f = ap::xy_frame;
namespace c = ap::xy_codec;

f::CommandFrame sample_command(std::uint16_t seq) {
  f::CommandFrame fr{seq, {c::CommandId::Jog, -2}, {c::CommandId::Goto, 123456}, {}};
  fr.subs[0] = {c::SubscriberId::BatteryMv, 0};
  fr.subs[1] = {c::SubscriberId::EncoderUm, 1};
  return fr;
}

f::EchoFrame sample_echo(std::uint16_t seq) {
  f::EchoFrame e{seq, {c::EchoStatus::ConstantSpeed, 45678}, {c::EchoStatus::Decelerating, -1234}, {}};
  e.subs[0] = {{c::SubscriberId::BatteryMv, 0}, 3712};
  e.subs[1] = {{c::SubscriberId::EncoderUm, 1}, 45001};
  return e;
}

void set_rate(benchmark::State& state, std::int64_t frames) {
  state.SetItemsProcessed(frames);
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
}

void BM_ProtocolParseCommand(benchmark::State& state) {
  std::array<std::uint8_t, c::kCommandLength> bytes{};
  if (!f::format_command(sample_command(17), bytes).ok()) state.SkipWithError("format failed");
  f::CommandFrame out;
  std::int64_t n = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bytes.data());
    const auto r = f::parse_command(bytes, out);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(out);
    ++n;
  }
  set_rate(state, n);
}
BENCHMARK(BM_ProtocolParseCommand);

void BM_ProtocolFormatCommand(benchmark::State& state) {
  std::array<std::uint8_t, c::kCommandLength> bytes{};
  auto fr = sample_command(0);
  std::int64_t n = 0;
  for (auto _ : state) {
    fr.seq = static_cast<std::uint16_t>((fr.seq + 1U) % c::kSeqModulo);
    const auto r = f::format_command(fr, bytes);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(bytes.data());
    ++n;
  }
  set_rate(state, n);
}
BENCHMARK(BM_ProtocolFormatCommand);

void BM_ProtocolParseEcho(benchmark::State& state) {
  std::array<std::uint8_t, c::kEchoLength> bytes{};
  if (!f::format_echo(sample_echo(17), bytes).ok()) state.SkipWithError("format failed");
  f::EchoFrame out;
  std::int64_t n = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bytes.data());
    const auto r = f::parse_echo(bytes, out);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(out);
    ++n;
  }
  set_rate(state, n);
}
BENCHMARK(BM_ProtocolParseEcho);

void BM_ProtocolFormatEcho(benchmark::State& state) {
  std::array<std::uint8_t, c::kEchoLength> bytes{};
  auto e = sample_echo(0);
  std::int64_t n = 0;
  for (auto _ : state) {
    e.seq = static_cast<std::uint16_t>((e.seq + 1U) % c::kSeqModulo);
    const auto r = f::format_echo(e, bytes);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(bytes.data());
    ++n;
  }
  set_rate(state, n);
}
BENCHMARK(BM_ProtocolFormatEcho);

// 100 frames with two bytes of line noise between them, framed and parsed.
void BM_ProtocolFramerStream(benchmark::State& state) {
  std::vector<std::uint8_t> stream;
  for (std::uint16_t i = 0; i < 100; ++i) {
    std::array<std::uint8_t, c::kCommandLength> bytes{};
    if (!f::format_command(sample_command(i), bytes).ok()) state.SkipWithError("format failed");
    stream.insert(stream.end(), bytes.begin(), bytes.end());
    stream.push_back('\r');
    stream.push_back('\n');
  }
  std::int64_t n = 0;
  for (auto _ : state) {
    f::CommandFramer framer;
    std::uint32_t accepted = 0;
    framer.feed(stream, [&](const f::CommandFramer::Event& e) { accepted += e.rejection.ok() ? 1U : 0U; });
    if (accepted != 100U) state.SkipWithError("framer lost frames");
    n += accepted;
  }
  set_rate(state, n);
}
BENCHMARK(BM_ProtocolFramerStream);

}  // namespace
