// The unit3 modules' small API, value by value (docs/unit3.md): the names of every error,
// refusal and source the tools print; the defensive reads past a table; the comparisons the
// tests and fuzz targets rely on telling different values apart; malformed replies.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "core/unit3/axis/counting.hpp"
#include "core/unit3/board/unit.hpp"
#include "core/unit3/joystick/joystick.hpp"
#include "core/unit3/menu/menu.hpp"
#include "core/unit3/settings/settings.hpp"
#include "protocol/unit3/wire/dialect.hpp"

namespace {

namespace w = ap::unit3_wire;
namespace u = ap::unit3_board;

std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(Unit3Api, ErrorRefusalAndSourceNamesAreTheDocumentedOnes) {
  // docs/unit3.md "The wire" and "Replies".
  const char* const line[] = {"none", "unknown_command", "bad_length", "bad_digit", "bad_sign",
                              "mode_out_of_range", "thread_out_of_range", "too_long"};
  for (std::uint8_t e = 0; e <= 7; ++e) EXPECT_STREQ(w::error_key(static_cast<w::Error>(e)), line[e]);
  EXPECT_STREQ(u::refusal_key(20), "busy");
  EXPECT_STREQ(u::refusal_key(21), "not_multiple");
  EXPECT_STREQ(u::refusal_key(22), "counter_range");
  EXPECT_STREQ(u::refusal_key(23), "endstop");
  EXPECT_EQ(u::refusal_key(19), nullptr);
  EXPECT_EQ(u::refusal_key(24), nullptr);
  EXPECT_STREQ(u::source_key(u::Source::Idle), "idle");
  EXPECT_STREQ(u::source_key(u::Source::Pc), "pc");
  EXPECT_STREQ(u::source_key(u::Source::Joystick), "joystick");
}

TEST(Unit3Api, ReadsPastATableStayInIt) {
  std::array<std::uint8_t, 8> eeprom{};
  eeprom.fill(0xFF);
  const u::Unit unit(eeprom);
  EXPECT_EQ(&unit.axis(3), &unit.axis(0));
  EXPECT_EQ(&unit.out(7), &unit.out(0));
  // 6400 counts are one turn: 400 µm on M2, the table's first thread.
  EXPECT_EQ(ap::unit3_axis::position_um(6400, 7), 400);
  ap::unit3_menu::State s;
  s.window = ap::unit3_menu::Window::StepSize;
  s.axis = 9;  // no press makes it
  ap::unit3_settings::Settings set{};
  ap::unit3_menu::press(s, set, ap::unit3_menu::Button::Right);
  EXPECT_EQ(s.axis, 0);
  EXPECT_EQ(set.mode[0], 1);
}

TEST(Unit3Api, ComparisonsTellValuesApart) {
  w::Command a;
  a.kind = w::Kind::Move;
  w::Command b = a;
  EXPECT_EQ(a, b);
  b.axis = w::Axis::Y;
  EXPECT_NE(a, b);
  b = a;
  b.count = 1;
  EXPECT_NE(a, b);
  b = a;
  b.sign[2] = -1;
  EXPECT_NE(a, b);
  b = a;
  b.digit[1] = 3;
  EXPECT_NE(a, b);
  b = a;
  b.kind = w::Kind::Get;
  EXPECT_NE(a, b);
  EXPECT_NE((w::Rejection{w::Error::BadDigit, 1}), (w::Rejection{w::Error::BadDigit, 2}));
  EXPECT_NE((w::Rejection{w::Error::BadDigit, 1}), (w::Rejection{w::Error::BadSign, 1}));
  EXPECT_NE((w::Report{w::Axis::X, 1}), (w::Report{w::Axis::X, 2}));
  EXPECT_NE((w::Report{w::Axis::X, 1}), (w::Report{w::Axis::Z, 1}));
  EXPECT_NE((w::Framer::Counters{1, 0}), (w::Framer::Counters{1, 1}));
  EXPECT_NE((w::Framer::Counters{1, 0}), (w::Framer::Counters{2, 0}));
  using D = ap::unit3_joystick::Deflection;
  EXPECT_NE((D{1, 3}), (D{1, 4}));
  EXPECT_NE((D{1, 3}), (D{-1, 3}));
  const auto& pins = ap::unit3_axis::kModePins;
  EXPECT_NE(pins[0], pins[4]);  // MODE2
  EXPECT_NE(pins[0], pins[2]);  // MODE1
  EXPECT_NE(pins[0], pins[1]);  // MODE0
  ap::unit3_settings::Settings s1{}, s2{};
  s2.thread[1] = 2;
  EXPECT_NE(s1, s2);
  s2 = s1;
  s2.mode[0] = 2;
  EXPECT_NE(s1, s2);
}

TEST(Unit3Api, MalformedRepliesAreNotRead) {
  EXPECT_EQ(w::parse_report(bytes("A+000000000000000001;")), std::nullopt);  // first byte before X
  EXPECT_EQ(w::parse_report(bytes("[+000000000000000001;")), std::nullopt);  // after Z
  EXPECT_EQ(w::parse_report(bytes("X*000000000000000001;")), std::nullopt);  // no sign
  EXPECT_EQ(w::parse_report(bytes("X+00000000000000000a;")), std::nullopt);  // not a digit
  EXPECT_EQ(w::parse_error(bytes("Ea1;")), std::nullopt);
  EXPECT_EQ(w::parse_error(bytes("E1a;")), std::nullopt);
  w::Command c;
  EXPECT_EQ(w::parse(bytes(""), c).error, w::Error::BadLength);  // an empty line has no command
  std::array<std::uint8_t, w::kReportLength> out{};
  EXPECT_EQ(w::format_report(static_cast<w::Axis>(3), 0, out), 0U);
  EXPECT_EQ(w::format_report(w::Axis::X, -1'000'000'000'000'000'000LL, out), 0U);
}

}  // namespace
