// The wire contract's properties (docs/protocol.md), over frames drawn from the codec tables.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <string>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "protocol/xy/codec/crc16.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/frame/fields.hpp"
#include "core/xy/frame/stream_framer.hpp"
#include "frame_gen.hpp"

namespace {

namespace f = ap::xy_frame;
namespace c = ap::xy_codec;
using ap::test::genCommand;
using ap::test::genEcho;

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

std::string with_fixed_crc(std::string b, std::size_t crc_offset) {
  std::vector<std::uint8_t> v(b.begin(), b.end());
  f::fields::write_hex16(v, crc_offset, f::fields::payload_crc(v, crc_offset));
  return {v.begin(), v.end()};
}

RC_GTEST_PROP(ProtocolProps, ParseOfFormatIsIdentityForCommands, ()) {
  const auto fr = *genCommand();
  const auto bytes = ap::xy_client::format(fr);
  RC_ASSERT(bytes.has_value());
  RC_ASSERT(bytes->size() == c::kCommandLength);
  f::CommandFrame back;
  RC_ASSERT(f::parse_command(bytes_of(*bytes), back).ok());
  RC_ASSERT(back == fr);
}

RC_GTEST_PROP(ProtocolProps, ParseOfFormatIsIdentityForEchoes, ()) {
  const auto fr = *genEcho();
  const auto bytes = ap::xy_client::format(fr);
  RC_ASSERT(bytes.has_value());
  f::EchoFrame back;
  RC_ASSERT(f::parse_echo(bytes_of(*bytes), back).ok());
  RC_ASSERT(back == fr);
}

// Accepted byte strings are drawn near valid frames: some payload characters replaced by
// field characters and the CRC repaired, so many are accepted and some are not.
RC_GTEST_PROP(ProtocolProps, FormatOfParseIsIdentityForAcceptedCommandBytes, ()) {
  auto b = *ap::xy_client::format(*genCommand());
  const auto edits = *rc::gen::inRange(1, 4);
  for (int i = 0; i < edits; ++i) {
    const auto at = *rc::gen::inRange<std::size_t>(c::kSeqOffset, c::kCommandCrcOffset);
    b[at] = *rc::gen::elementOf(std::string("0123456789-+ "));
  }
  b = with_fixed_crc(b, c::kCommandCrcOffset);
  f::CommandFrame fr;
  const bool accepted = f::parse_command(bytes_of(b), fr).ok();
  RC_TAG(accepted ? "accepted" : "rejected");
  if (accepted) RC_ASSERT(ap::xy_client::format(fr) == std::optional<std::string>(b));
}

RC_GTEST_PROP(ProtocolProps, FormatOfParseIsIdentityForAcceptedEchoBytes, ()) {
  auto b = *ap::xy_client::format(*genEcho());
  const auto at = *rc::gen::inRange<std::size_t>(c::kSeqOffset, c::kEchoCrcOffset);
  b[at] = *rc::gen::elementOf(std::string("0123456789-"));
  b = with_fixed_crc(b, c::kEchoCrcOffset);
  f::EchoFrame fr;
  const bool accepted = f::parse_echo(bytes_of(b), fr).ok();
  RC_TAG(accepted ? "accepted" : "rejected");
  if (accepted) RC_ASSERT(ap::xy_client::format(fr) == std::optional<std::string>(b));
}

// A stream of valid frames, corrupted frames, truncated frames and garbage.
std::string gen_stream() {
  std::string s;
  const auto pieces = *rc::gen::inRange(0, 8);
  for (int i = 0; i < pieces; ++i) {
    auto frame = *ap::xy_client::format(*genCommand());
    switch (*rc::gen::inRange(0, 4)) {
      case 0: s += frame; break;
      case 1: frame[*rc::gen::inRange<std::size_t>(0, frame.size())] ^= static_cast<char>(1 << *rc::gen::inRange(0, 8)); s += frame; break;
      case 2: s += frame.substr(0, *rc::gen::inRange<std::size_t>(0, frame.size())); break;
      default: {
        const auto garbage = *rc::gen::container<std::vector<char>>(rc::gen::arbitrary<char>());
        s.append(garbage.begin(), garbage.end());
      }
    }
  }
  return s;
}

struct Run {
  std::vector<f::CommandFramer::Event> events;
  f::FramerCounters counters;
  std::size_t pending = 0;
  bool operator==(const Run&) const = default;
};

Run frame_in_chunks(const std::string& s, const std::vector<std::size_t>& cuts) {
  f::CommandFramer framer;
  Run run;
  std::size_t from = 0;
  for (std::size_t cut : cuts) {
    cut = std::min(std::max(cut, from), s.size());
    framer.feed(bytes_of(s).subspan(from, cut - from), [&](const auto& e) { run.events.push_back(e); });
    from = cut;
  }
  framer.feed(bytes_of(s).subspan(from), [&](const auto& e) { run.events.push_back(e); });
  run.counters = framer.counters();
  run.pending = framer.pending();
  return run;
}

RC_GTEST_PROP(ProtocolProps, ChunkingDoesNotChangeFramesOrErrors, ()) {
  const auto s = gen_stream();
  auto cuts = *rc::gen::container<std::vector<std::size_t>>(rc::gen::inRange<std::size_t>(0, s.size() + 1));
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::size_t> every_byte(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) every_byte[i] = i;
  const Run whole = frame_in_chunks(s, {});
  RC_ASSERT(frame_in_chunks(s, cuts) == whole);
  RC_ASSERT(frame_in_chunks(s, every_byte) == whole);
  // Every byte is accounted for exactly once: accepted, rejected, or still pending.
  RC_ASSERT(whole.counters.rejected_bytes + whole.counters.accepted_frames * c::kCommandLength + whole.pending ==
            s.size());
}

RC_GTEST_PROP(ProtocolProps, GarbageBeforeOrBetweenFramesLosesNoValidFrame, ()) {
  const auto frames = *rc::gen::container<std::vector<f::CommandFrame>>(genCommand());
  std::string s;
  for (const auto& fr : frames) {
    const auto garbage = *rc::gen::container<std::vector<char>>(rc::gen::arbitrary<char>());
    s.append(garbage.begin(), garbage.end());
    s += *ap::xy_client::format(fr);
  }
  const auto tail = *rc::gen::container<std::vector<char>>(rc::gen::arbitrary<char>());
  s.append(tail.begin(), tail.end());
  std::vector<f::CommandFrame> got;
  f::CommandFramer framer;
  framer.feed(bytes_of(s), [&](const auto& e) {
    if (e.rejection.ok()) got.push_back(e.frame);
  });
  RC_ASSERT(got == frames);
}

// Exhaustive over single bits, random over pairs (golden test does all pairs for its frames).
template <class Frame, class Parse>
void check_bit_errors(const std::string& good, Parse parse) {
  const std::size_t bits = good.size() * 8;
  const auto flip = [&](std::string s, std::size_t i) {
    s[i / 8] = static_cast<char>(s[i / 8] ^ (1 << (i % 8)));
    return s;
  };
  for (std::size_t i = 0; i < bits; ++i) {
    Frame out{};
    out.seq = 999;
    const Frame before = out;
    RC_ASSERT(!parse(bytes_of(flip(good, i)), out).ok());
    RC_ASSERT(out == before);
  }
  for (int k = 0; k < 200; ++k) {
    const auto i = *rc::gen::inRange<std::size_t>(0, bits);
    const auto j = *rc::gen::distinctFrom(rc::gen::inRange<std::size_t>(0, bits), i);
    Frame out{};
    RC_ASSERT(!parse(bytes_of(flip(flip(good, i), j)), out).ok());
  }
}

RC_GTEST_PROP(ProtocolProps, EverySingleAndDoubleBitErrorIsRejected, ()) {
  check_bit_errors<f::CommandFrame>(*ap::xy_client::format(*genCommand()), f::parse_command);
  check_bit_errors<f::EchoFrame>(*ap::xy_client::format(*genEcho()), f::parse_echo);
}

}  // namespace
