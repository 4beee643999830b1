// Properties of the `;` dialect (docs/unit3.md "The wire"): every command the formatter writes
// reads back as itself, and a byte lost anywhere in a stream of commands (19200 baud, no
// checksum) never makes the unit run a command the PC did not send: what it accepts is the
// sent sequence with at most the command the byte was in and, if the lost byte was a ';',
// the one after it.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "protocol/unit3/wire/dialect.hpp"

namespace {

namespace w = ap::unit3_wire;

rc::Gen<w::Command> gen_command() {
  return rc::gen::exec([] {
    w::Command c;
    c.kind = *rc::gen::element(w::Kind::Direction, w::Kind::Move, w::Kind::StepMode, w::Kind::Thread,
                               w::Kind::Clear, w::Kind::Get);
    switch (c.kind) {
      case w::Kind::Move:
        c.axis = *rc::gen::element(w::Axis::X, w::Axis::Y, w::Axis::Z);
        c.count = *rc::gen::oneOf(rc::gen::inRange<std::uint64_t>(0, 100000),
                                  rc::gen::inRange<std::uint64_t>(0, w::kMaxCount + 1),
                                  rc::gen::just(w::kMaxCount));
        break;
      case w::Kind::Direction:
        for (auto& s : c.sign) s = *rc::gen::element<std::int8_t>(1, -1);
        break;
      case w::Kind::StepMode:
        for (auto& d : c.digit) d = *rc::gen::inRange<std::uint8_t>(0, w::kMaxModeDigit + 1);
        break;
      case w::Kind::Thread:
        for (auto& d : c.digit) d = *rc::gen::inRange<std::uint8_t>(0, w::kMaxThreadDigit + 1);
        break;
      default: break;
    }
    return c;
  });
}

std::string line_of(const w::Command& c) {
  std::array<std::uint8_t, w::kMaxLine> out{};
  const std::size_t n = w::format(c, out);
  RC_ASSERT(n > 0U);
  return {reinterpret_cast<const char*>(out.data()), n};
}

std::vector<w::Command> accepted(const std::string& stream) {
  w::Framer f;
  std::vector<w::Command> got;
  f.feed({reinterpret_cast<const std::uint8_t*>(stream.data()), stream.size()}, [&](const w::Framer::Event& e) {
    if (e.rejection.ok()) got.push_back(e.command);
  });
  return got;
}

RC_GTEST_PROP(Unit3WireProps, FormatThenParseIsIdentity, ()) {
  const w::Command c = *gen_command();
  const std::string s = line_of(c);
  w::Command back;
  const auto r = w::parse({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}, back);
  RC_ASSERT(r.ok());
  RC_ASSERT(back == c);
}

RC_GTEST_PROP(Unit3WireProps, ALostByteNeverRunsACommandThatWasNotSent, ()) {
  const auto sent = *rc::gen::container<std::vector<w::Command>>(*rc::gen::inRange<std::size_t>(1, 12), gen_command());
  std::string stream;
  std::vector<std::size_t> owner;  // which command each byte belongs to
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const std::string s = line_of(sent[i]);
    stream += s;
    owner.insert(owner.end(), s.size(), i);
  }
  RC_ASSERT(accepted(stream) == sent);
  const auto k = *rc::gen::inRange<std::size_t>(0, stream.size());
  const bool was_end = stream[k] == ';';
  const std::size_t hit = owner[k];
  std::string lossy = stream;
  lossy.erase(k, 1);
  std::vector<w::Command> expect;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    if (i == hit || (was_end && i == hit + 1)) continue;
    expect.push_back(sent[i]);
  }
  RC_ASSERT(accepted(lossy) == expect);
}

// However the stream is cut into chunks, the same events come out.
RC_GTEST_PROP(Unit3WireProps, ChunkingDoesNotChangeTheEvents, ()) {
  const auto bytes = *rc::gen::container<std::string>(rc::gen::oneOf(
      rc::gen::element('X', 'Y', 'Z', 'D', 'M', 'T', 'C', 'G', ';', '+', '-', '\r', '\n'),
      rc::gen::inRange('0', static_cast<char>('9' + 1)), rc::gen::arbitrary<char>()));
  const auto events = [](const std::string& s, std::size_t chunk) {
    w::Framer f;
    std::vector<std::pair<std::uint32_t, w::Rejection>> out;
    for (std::size_t i = 0; i < s.size(); i += chunk) {
      const std::string part = s.substr(i, chunk);
      f.feed({reinterpret_cast<const std::uint8_t*>(part.data()), part.size()},
             [&](const w::Framer::Event& e) { out.emplace_back(e.stream_offset, e.rejection); });
    }
    return out;
  };
  const auto chunk = *rc::gen::inRange<std::size_t>(1, 20);
  RC_ASSERT(events(bytes, chunk) == events(bytes, bytes.size() + 1));
}

}  // namespace
