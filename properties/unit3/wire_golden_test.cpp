// The `;` dialect against the thesis's own strings (seed 001 §2.3) and the decisions of
// docs/unit3.md "The wire": every expected value below is written from those texts, not
// computed with the code under test.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/unit3/wire/dialect.hpp"

namespace {

namespace w = ap::unit3_wire;

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

w::Command parsed(const std::string& s) {
  w::Command c;
  const auto r = w::parse(bytes_of(s), c);
  EXPECT_TRUE(r.ok()) << s << ": " << w::error_key(r.error) << " at " << int{r.offset};
  return c;
}

w::Rejection rejection(const std::string& s) {
  w::Command c;
  return w::parse(bytes_of(s), c);
}

std::string formatted(const w::Command& c) {
  std::array<std::uint8_t, w::kMaxLine> out{};
  const std::size_t n = w::format(c, out);
  return {reinterpret_cast<const char*>(out.data()), n};
}

// The thesis's two examples: Y, full step, 500 steps = 500 x 32 x 1 = 16000 counts; Y, 1/32
// step, 500 microsteps = 500 x 32 x 1/32 = 500 counts.
TEST(Unit3Wire, ThesisExamplesAreMovesOfY) {
  const auto full = parsed("Y000000000016000;");
  EXPECT_EQ(full.kind, w::Kind::Move);
  EXPECT_EQ(full.axis, w::Axis::Y);
  EXPECT_EQ(full.count, 16000U);
  const auto micro = parsed("Y000000000000500;");
  EXPECT_EQ(micro.kind, w::Kind::Move);
  EXPECT_EQ(micro.axis, w::Axis::Y);
  EXPECT_EQ(micro.count, 500U);
  EXPECT_EQ(formatted(full), "Y000000000016000;");
  EXPECT_EQ(formatted(micro), "Y000000000000500;");
}

TEST(Unit3Wire, EveryCommandOfTheThesis) {
  const auto d = parsed("D+-+;");
  EXPECT_EQ(d.kind, w::Kind::Direction);
  EXPECT_EQ(d.sign, (std::array<std::int8_t, 3>{1, -1, 1}));
  const auto m = parsed("M505;");
  EXPECT_EQ(m.kind, w::Kind::StepMode);
  EXPECT_EQ(m.digit, (std::array<std::uint8_t, 3>{5, 0, 5}));
  const auto t = parsed("T046;");
  EXPECT_EQ(t.kind, w::Kind::Thread);
  EXPECT_EQ(t.digit, (std::array<std::uint8_t, 3>{0, 4, 6}));
  EXPECT_EQ(parsed("C;").kind, w::Kind::Clear);
  EXPECT_EQ(parsed("G;").kind, w::Kind::Get);
  EXPECT_EQ(parsed("X999999999999999;").count, 999'999'999'999'999ULL);
  EXPECT_EQ(parsed("Z000000000000000;").axis, w::Axis::Z);
  for (const std::string s : {"D+-+;", "M505;", "T046;", "C;", "G;", "X999999999999999;"}) {
    EXPECT_EQ(formatted(parsed(s)), s);
  }
}

TEST(Unit3Wire, TypedErrorsNameTheByte) {
  using E = w::Error;
  EXPECT_EQ(rejection("Q;"), (w::Rejection{E::UnknownCommand, 0}));
  EXPECT_EQ(rejection("y000000000016000;"), (w::Rejection{E::UnknownCommand, 0}));  // upper case only
  EXPECT_EQ(rejection("Y00000000016000;"), (w::Rejection{E::BadLength, 15}));       // 14 digits: a lost byte
  EXPECT_EQ(rejection("Y0000000000160000;"), (w::Rejection{E::BadLength, 16}));     // 16 digits: no ; at 16
  EXPECT_EQ(rejection("Y00000000001600a;"), (w::Rejection{E::BadDigit, 15}));
  EXPECT_EQ(rejection("Y-00000000016000;"), (w::Rejection{E::BadDigit, 1}));        // unsigned: D gives direction
  EXPECT_EQ(rejection("M506;"), (w::Rejection{E::ModeOutOfRange, 3}));
  EXPECT_EQ(rejection("M905;"), (w::Rejection{E::ModeOutOfRange, 1}));
  EXPECT_EQ(rejection("T070;"), (w::Rejection{E::ThreadOutOfRange, 2}));
  EXPECT_EQ(rejection("T009;"), (w::Rejection{E::ThreadOutOfRange, 3}));
  EXPECT_EQ(rejection("T0x0;"), (w::Rejection{E::BadDigit, 2}));
  EXPECT_EQ(rejection("D+*+;"), (w::Rejection{E::BadSign, 2}));
  EXPECT_EQ(rejection("D++;"), (w::Rejection{E::BadLength, 3}));
  EXPECT_EQ(rejection("C0;"), (w::Rejection{E::BadLength, 1}));
  EXPECT_EQ(rejection("G"), (w::Rejection{E::BadLength, 0}));  // the line ends before its ;
}

TEST(Unit3Wire, OutOfRangeFieldsAreNotFormatted) {
  w::Command c;
  c.kind = w::Kind::Move;
  c.count = 1'000'000'000'000'000ULL;  // 16 digits
  EXPECT_EQ(formatted(c), "");
  c = {};
  c.kind = w::Kind::StepMode;
  c.digit = {0, 6, 0};
  EXPECT_EQ(formatted(c), "");
  c.kind = w::Kind::Thread;
  c.digit = {7, 0, 0};
  EXPECT_EQ(formatted(c), "");
  c = {};
  c.kind = w::Kind::Direction;
  c.sign = {1, 0, -1};
  EXPECT_EQ(formatted(c), "");
}

// Counter reports: X|Y|Z, a sign, 18 digits, ';' (docs/unit3.md "The wire").
TEST(Unit3Wire, CounterReportsHaveOneWidth) {
  std::array<std::uint8_t, w::kReportLength> out{};
  ASSERT_EQ(w::format_report(w::Axis::Y, 16000, out), 21U);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data()), 21), "Y+000000000000016000;");
  ASSERT_EQ(w::format_report(w::Axis::Z, -500, out), 21U);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data()), 21), "Z-000000000000000500;");
  EXPECT_EQ(w::format_report(w::Axis::X, 1'000'000'000'000'000'000LL, out), 0U);
  EXPECT_EQ(w::parse_report(bytes_of("X+999999999999999999;")), (w::Report{w::Axis::X, 999'999'999'999'999'999LL}));
  EXPECT_EQ(w::parse_report(bytes_of("X-000000000000000000;")), std::nullopt);  // zero is +0
  EXPECT_EQ(w::parse_report(bytes_of("X+00000000000000000;")), std::nullopt);   // 17 digits
}

// The unit's refusal reply E<2 digits>; (docs/unit3.md "Replies").
TEST(Unit3Wire, ErrorReplies) {
  std::array<std::uint8_t, 4> out{};
  ASSERT_EQ(w::format_error(2, out), 4U);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data()), 4), "E02;");
  ASSERT_EQ(w::format_error(23, out), 4U);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out.data()), 4), "E23;");
  EXPECT_EQ(w::format_error(0, out), 0U);
  EXPECT_EQ(w::format_error(100, out), 0U);
  EXPECT_EQ(w::parse_error(bytes_of("E20;")), std::optional<std::uint8_t>(20));
  EXPECT_EQ(w::parse_error(bytes_of("E00;")), std::nullopt);
  EXPECT_EQ(w::parse_error(bytes_of("E2;")), std::nullopt);
  EXPECT_EQ(w::parse_error(bytes_of("E2x;")), std::nullopt);
  EXPECT_EQ(w::parse_error(bytes_of("F20;")), std::nullopt);
  EXPECT_EQ(w::parse_error(bytes_of("E201")), std::nullopt);
}

// The framer: split and joined chunks, line ends between commands, an over-long line.
TEST(Unit3Wire, FramerCutsAStreamAtSemicolons) {
  w::Framer f;
  std::vector<w::Framer::Event> ev;
  const std::string s = "D+++;\r\nY000000000016000;M505;C;garbage-without-end-that-runs-on;G;";
  f.feed(bytes_of(s.substr(0, 9)), [&](const auto& e) { ev.push_back(e); });
  f.feed(bytes_of(s.substr(9)), [&](const auto& e) { ev.push_back(e); });
  ASSERT_EQ(ev.size(), 6U);
  EXPECT_EQ(ev[0].command.kind, w::Kind::Direction);
  EXPECT_EQ(ev[1].command.count, 16000U);
  EXPECT_EQ(ev[1].stream_offset, 7U);  // after "D+++;\r\n"
  EXPECT_EQ(ev[2].command.kind, w::Kind::StepMode);
  EXPECT_EQ(ev[3].command.kind, w::Kind::Clear);
  EXPECT_EQ(ev[4].rejection.error, w::Error::TooLong);
  EXPECT_EQ(ev[5].command.kind, w::Kind::Get);
  EXPECT_EQ(f.counters(), (w::Framer::Counters{5, 1}));
  EXPECT_EQ(f.pending(), 0U);
}

}  // namespace
