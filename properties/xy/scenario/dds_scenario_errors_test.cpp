// The scenario parser's rejections and the less common statements (docs/scenarios.md):
// every malformed statement is a ParseError (the shared kit's) naming the file, the line and
// the problem; every verb, setup key, subject family and unit parses to the documented
// canonical value; the printer covers every optional part; holds() applies every operator; the
// equality used by the round-trip property distinguishes every field.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "sim/xy/scenario.hpp"

namespace sc = ap::sim::xy::scenario;

namespace {

const std::string kHead = "scenario t\nduration 10 s\n";

// The message of the ParseError parse() throws (file "t.scn"), or "no error".
std::string error_of(const std::string& text) {
  try {
    (void)sc::parse(text, "t.scn");
  } catch (const sc::ParseError& e) {
    return e.what();
  }
  return "no error";
}

sc::Scenario without_lines(sc::Scenario s) {
  for (auto& a : s.actions) a.line = 0;
  for (auto& e : s.expectations) e.line = 0;
  for (auto& f : s.faults) f.line = 0;
  for (auto& st : s.setup) st.line = 0;
  return s;
}

sc::Scenario round_trip(const sc::Scenario& s) { return without_lines(sc::parse(sc::to_text(s), "printed")); }

// A word missing at the end of a statement and a word left over after it are the shared kit's
// messages (sim/scenario_text.hpp, the dialect that names the missing word): "expected X at the
// end of the line" and "unexpected 'W' at the end of the line". They say what the parser said
// before it read its lines with the kit ("expected X", "unexpected 'W'"), and where.
struct Bad {
  std::string text;      // appended to kHead unless `whole`
  std::string message;   // expected e.what()
  bool whole = false;
};

}  // namespace

TEST(dds_scenario_errors, HeaderStatementsAreChecked) {
  const std::vector<Bad> cases{
      {"", "t.scn:1: empty scenario (no 'scenario NAME' line)", true},
      {"# only a comment\n\n", "t.scn:3: empty scenario (no 'scenario NAME' line)", true},
      {"scenario T\n", "t.scn:1: scenario name must be [a-z0-9_-]+", true},
      {"scenario a!\n", "t.scn:1: scenario name must be [a-z0-9_-]+", true},
      {"scenario a~\n", "t.scn:1: scenario name must be [a-z0-9_-]+", true},
      {"scenario\n", "t.scn:1: expected a scenario name at the end of the line", true},
      {"scenario t\nscenario u\n", "t.scn:2: second 'scenario' line", true},
      {"scenario t\nduration 0 s\n", "t.scn:2: duration must be positive", true},
      {"scenario t\nduration -5 s\n", "t.scn:2: run duration must not be negative", true},
      {"scenario t\nduration 5 mm\n", "t.scn:2: run duration: expected a time (us, ms, s, min), got a length (um, mm, ...)", true},
      {"scenario t\nduration 5\n", "t.scn:2: run duration: '5' needs a unit: a time (us, ms, s, min)", true},
      {"scenario t\nduration 1 s\nunknown\n", "t.scn:3: unknown keyword 'unknown'", true},
      {"period 0 ms\n", "t.scn:3: period must be positive"},
      {"boards 0\n", "t.scn:3: boards must be 1..64"},
      {"boards 65\n", "t.scn:3: boards must be 1..64"},
      {"boards 2.5\n", "t.scn:3: boards must be 1..64"},
      {"boards 2 mm\n", "t.scn:3: board count: expected a plain number, got a length (um, mm, ...)"},
      {"expect end gaps == 0\nboards 2\n", "t.scn:4: 'boards' must come before actions and expectations"},
      {"baud 299\n", "t.scn:3: baud must be 300..4000000"},
      {"baud 4000001\n", "t.scn:3: baud must be 300..4000000"},
      {"timing fast\n", "t.scn:3: timing must be lockstep|realtime, got 'fast'"},
      {"title untitled\n", "t.scn:3: title must be a \"quoted string\""},
      {"title x\n", "t.scn:3: title must be a \"quoted string\""},
      {"title \"a\\", "t.scn:3: unterminated string"},
      {"seed abc\n", "t.scn:3: expected seed, got 'abc'"},
      {"seed .\n", "t.scn:3: bad number '.'"},
      {"seed 1.2.3\n", "t.scn:3: bad number '1.2.3'"},
      {"period 5 furlongs\n", "t.scn:3: command period: '5' needs a unit: a time (us, ms, s, min)"},
      {"period 5furlongs\n", "t.scn:3: unknown unit 'furlongs'"},
      {"period 3ex\n", "t.scn:3: unknown unit 'ex'"},
      {"period 1e-.\n", "t.scn:3: unknown unit 'e-.'"},
  };
  for (const Bad& b : cases) {
    SCOPED_TRACE(b.text);
    EXPECT_EQ(error_of(b.whole ? b.text : kHead + b.text), b.message);
  }
}

TEST(dds_scenario_errors, ParseErrorCarriesFileAndLine) {
  try {
    (void)sc::parse(kHead + "\n\nat 1 s fly\n", "dir/f.scn");
    FAIL() << "no error";
  } catch (const sc::ParseError& e) {
    EXPECT_EQ(e.file(), "dir/f.scn");
    EXPECT_EQ(e.line(), 5);
  }
  try {
    (void)sc::parse_file("/nonexistent/axisproof/none.scn");
    FAIL() << "no error";
  } catch (const sc::ParseError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/axisproof/none.scn");
    EXPECT_EQ(e.line(), 0);
    EXPECT_STREQ(e.what(), "/nonexistent/axisproof/none.scn:0: cannot open");
  }
}

TEST(dds_scenario_errors, SetupAndFaultStatementsAreChecked) {
  const std::vector<Bad> cases{
      {"board wifi on\n", "t.scn:3: board setting must be battery|charger|usb|ble|temperature|pos|endstop|encoder|param|fram, got 'wifi'"},
      {"board battery 3 A\n", "t.scn:3: battery voltage: expected a voltage (mV, V), got a current (mA, A)"},
      {"board battery -3 V\n", "t.scn:3: battery voltage must not be negative"},
      {"board usb maybe\n", "t.scn:3: usb must be plugged|unplugged, got 'maybe'"},
      {"board ble on\n", "t.scn:3: BLE state must be shutdown|standby|connected|session, got 'on'"},
      {"board temperature 20 V\n", "t.scn:3: temperature: expected a temperature (mdegC, degC), got a voltage (mV, V)"},
      {"board pos z 1 mm\n", "t.scn:3: axis must be x or y, got 'z'"},
      {"board endstop x mid 1 mm\n", "t.scn:3: endstop must be min|max, got 'mid'"},
      {"board fram accel 5 mm\n", "t.scn:3: fram values are raw integers"},
      {"board param acc@l 5\n", "t.scn:3: expected a parameter name, got 'acc@l'"},
      {"board ble session extra\n", "t.scn:3: unexpected 'extra' at the end of the line"},
      {"fault lose 5 %\n", "t.scn:3: fault kind must be drop|duplicate|reorder|corrupt|delay, got 'lose'"},
      {"fault drop 5 ms\n", "t.scn:3: fault rate: expected a rate in %, got a time (us, ms, s, min)"},
      {"fault delay 5 %\n", "t.scn:3: delay: expected a time (us, ms, s, min), got a rate in %"},
      {"fault delay 5 ms jitter 1 %\n", "t.scn:3: jitter: expected a time (us, ms, s, min), got a rate in %"},
      {"fault drop 5 % sideways\n", "t.scn:3: fault direction (or from T [to T]) must be both|to_board|to_pc, got 'sideways'"},
      {"fault drop 5 % from 2 s to 1 s\n", "t.scn:3: fault ends before it starts"},
      {"fault drop 5 % from 11 s\n", "t.scn:3: fault starts after the end of the run"},
      {"fault drop 5 % from\n", "t.scn:3: expected fault start at the end of the line"},
  };
  for (const Bad& b : cases) {
    SCOPED_TRACE(b.text);
    EXPECT_EQ(error_of(kHead + b.text), b.message);
  }
}

TEST(dds_scenario_errors, ActionsAreChecked) {
  const std::vector<Bad> cases{
      {"at\n", "t.scn:3: expected action time at the end of the line"},
      {"at 1 s\n", "t.scn:3: expected an action at the end of the line"},
      {"at 1 s set\n", "t.scn:3: expected the rest of the action at the end of the line"},
      {"at 1 s set jerk 5\n", "t.scn:3: unknown action 'set jerk'"},
      {"at 1 s link up\n", "t.scn:3: unknown action 'link up'"},
      {"at abc stop x\n", "t.scn:3: expected action time, got 'abc'"},
      {"at -1 s stop x\n", "t.scn:3: action time must not be negative"},
      {"at 1 s @x stop x\n", "t.scn:3: bad board selector '@x'"},
      {"at 1 s @0x stop x\n", "t.scn:3: bad board selector '@0x'"},
      {"at 1 s jog x up\n", "t.scn:3: jog direction must be +|-, got 'up'"},
      {"at 1 s jog x + medium\n", "t.scn:3: jog speed must be fast|slow, got 'medium'"},
      {"at 1 s stop\n", "t.scn:3: expected an axis (x or y) at the end of the line"},
      {"at 1 s move x 5 mm/s\n", "t.scn:3: distance: expected a length (um, mm, ...), got a speed (um/s, mm/s, ...)"},
      {"at 1 s set speed medium 5 mm/s\n", "t.scn:3: speed level must be fast|slow, got 'medium'"},
      {"at 1 s set speed fast -5 mm/s\n", "t.scn:3: speed must not be negative"},
      {"at 1 s set accel 5 mm\n",
       "t.scn:3: acceleration: expected an acceleration (um/s2, mm/s2, ...), got a length (um, mm, ...)"},
      {"at 1 s save now\n", "t.scn:3: unexpected 'now' at the end of the line"},
      {"at 1 s subscribe humidity\n",
       "t.scn:3: subscriber must be battery|charge_current|temperature|rotation|all, got 'humidity'"},
      {"at 1 s usb on\n", "t.scn:3: plug state must be plug|unplug, got 'on'"},
      {"at 1 s battery 3 mdegC\n",
       "t.scn:3: battery voltage: expected a voltage (mV, V), got a temperature (mdegC, degC)"},
      {"at 1 s temperature 3 mdeg\n",
       "t.scn:3: temperature: expected a temperature (mdegC, degC), got an angle (mdeg, deg)"},
      {"at 1 s rotate 3 mA\n", "t.scn:3: rotation: expected an angle (mdeg, deg), got a current (mA, A)"},
      {"at 1 s ble off\n", "t.scn:3: BLE state (Tab. 7-2) must be shutdown|standby|connected|session, got 'off'"},
      {"at 1 s tmc x I*RUN 12\n", "t.scn:3: expected a TMC2130 field name, got 'I*RUN'"},
      {"at 1 s tmc x I~RUN 12\n", "t.scn:3: expected a TMC2130 field name, got 'I~RUN'"},
      {"at 1 s tmc x IRUN -1\n", "t.scn:3: field value must not be negative"},
      {"at 1 s tmc x IRUN 12 mA\n", "t.scn:3: field value: expected a plain number, got a current (mA, A)"},
      {"at 1 s link cut 2 mm\n", "t.scn:3: cut duration: expected a time (us, ms, s, min), got a length (um, mm, ...)"},
      {"at 1 s link restore now\n", "t.scn:3: unexpected 'now' at the end of the line"},
      {"at 1 s peripherals dim\n", "t.scn:3: peripherals must be on|off, got 'dim'"},
      {"at 1 s endstop x mid on\n", "t.scn:3: endstop must be min|max, got 'mid'"},
      {"at 1 s endstop x min maybe\n", "t.scn:3: endstop state must be on|off, got 'maybe'"},
      {"at 1 s button tap\n", "t.scn:3: button action must be press|hold, got 'tap'"},
      {"at 1 s raw 0100\n", "t.scn:3: raw frame must be a \"quoted string\""},
      {"at 1 s raw\n", "t.scn:3: expected a \"quoted\" frame at the end of the line"},
  };
  for (const Bad& b : cases) {
    SCOPED_TRACE(b.text);
    EXPECT_EQ(error_of(kHead + b.text), b.message);
  }
}

TEST(dds_scenario_errors, ExpectationsAreChecked) {
  const std::vector<Bad> cases{
      {"expect soon x.pos == 1 mm\n",
       "t.scn:3: expectation time (at|always|from|by|end) must be at|always|from|by|end, got 'soon'"},
      {"expect from 1 s x.pos == 1 mm\n", "t.scn:3: expected 'to'"},
      {"expect from 2 s to 1 s x.pos == 1 mm\n", "t.scn:3: window ends before it starts"},
      {"expect from 1 s to 11 s x.pos == 1 mm\n", "t.scn:3: expectation after the end of the run"},
      {"expect by 12 s x.status == reached\n", "t.scn:3: expectation after the end of the run"},
      {"expect at 1 s\n", "t.scn:3: expected a subject at the end of the line"},
      {"expect at 1 s x.pos\n", "t.scn:3: expected a comparison (== != < <= > >=) at the end of the line"},
      {"expect at 1 s x.pos =< 1 mm\n", "t.scn:3: unknown comparison '=<'"},
      {"expect at 1 s x.pos ==\n", "t.scn:3: subject x.pos needs a length (um, mm, ...)"},
      {"expect end gaps ==\n", "t.scn:3: expected an expected value at the end of the line"},
      {"expect at 1 s x.status == re@ched\n", "t.scn:3: expected an expected value, got 're@ched'"},
      {"expect at 1 s x.status == reached tol 1\n", "t.scn:3: a tolerance needs a numeric value"},
      {"expect at 1 s x.pos == 1 mm tol -1 um\n", "t.scn:3: tolerance must not be negative"},
      {"expect at 1 s x.pos == 1 mm tol\n", "t.scn:3: expected tolerance at the end of the line"},
      {"expect at 1 s x.speed >= +a\n", "t.scn:3: subject x.speed needs a speed (um/s, mm/s, ...)"},
      {"expect at 1 s board.battery == 3 mA\n",
       "t.scn:3: expected value: expected a voltage (mV, V), got a current (mA, A)"},
      {"expect at 1 s board.charge_current == 3 V\n",
       "t.scn:3: expected value: expected a current (mA, A), got a voltage (mV, V)"},
      {"expect at 1 s board.temperature > 3 %\n",
       "t.scn:3: expected value: expected a temperature (mdegC, degC), got a rate in %"},
      {"expect at 1 s board.rotation < 3 s\n",
       "t.scn:3: expected value: expected an angle (mdeg, deg), got a time (us, ms, s, min)"},
      {"expect at 1 s param.speed_slow == 3 mm\n",
       "t.scn:3: expected value: expected a speed (um/s, mm/s, ...), got a length (um, mm, ...)"},
  };
  for (const Bad& b : cases) {
    SCOPED_TRACE(b.text);
    EXPECT_EQ(error_of(kHead + b.text), b.message);
  }
}

TEST(dds_scenario_errors, UnknownSubjectsAreRejected) {
  for (const char* subject : {"x", "xy", "xpos", "x.foo", "y.velocity", "board.colour", "param.Bad", "param.",
                              "echo.z.id", "tmc.x.", "tmc.z.IRUN", "fram.Bad", "fram.", "sub.", "sub.BAT", "gap"}) {
    SCOPED_TRACE(subject);
    EXPECT_FALSE(sc::subject_dim(subject).has_value());
    EXPECT_EQ(error_of(kHead + "expect end " + subject + " == 0\n"), std::string("t.scn:3: unknown subject '") + subject + "'");
  }
}

TEST(dds_scenario_errors, SubjectDimensions) {
  const std::vector<std::pair<std::string, sc::Dim>> table{
      {"x.pos", sc::Dim::length},          {"y.target", sc::Dim::length},     {"y.speed", sc::Dim::speed},
      {"x.dir", sc::Dim::none},            {"y.status", sc::Dim::none},       {"x.endstop_min", sc::Dim::none},
      {"x.endstop_max", sc::Dim::none},    {"y.enabled", sc::Dim::none},      {"y.blocked", sc::Dim::none},
      {"x.lost_steps", sc::Dim::none},     {"board.battery", sc::Dim::voltage},
      {"board.charge_current", sc::Dim::current},                            {"board.temperature", sc::Dim::temperature},
      {"board.rotation", sc::Dim::angle},  {"board.state", sc::Dim::none},    {"board.led", sc::Dim::none},
      {"board.ble", sc::Dim::none},        {"board.charger", sc::Dim::none},  {"board.usb", sc::Dim::none},
      {"board.low_battery", sc::Dim::none}, {"board.peripherals", sc::Dim::none},
      {"param.accel", sc::Dim::accel},     {"param.speed_fast", sc::Dim::speed},
      {"param.speed_slow", sc::Dim::speed}, {"param.lead", sc::Dim::length},  {"param.microsteps", sc::Dim::none},
      {"echo.count", sc::Dim::none},       {"echo.x.id", sc::Dim::none},      {"echo.y.id", sc::Dim::none},
      {"echo.x.data", sc::Dim::none},      {"echo.y.data", sc::Dim::none},    {"echo.last", sc::Dim::none},
      {"tmc.x.IRUN", sc::Dim::none},       {"tmc.y.TPOWER_DOWN", sc::Dim::none},
      {"fram.accel", sc::Dim::none},       {"sub.battery", sc::Dim::none},    {"sub.charge_current", sc::Dim::none},
      {"gaps", sc::Dim::none},             {"commands", sc::Dim::none},       {"echoes", sc::Dim::none},
      {"rejected", sc::Dim::none},         {"watchdog_stops", sc::Dim::none}, {"lost_steps", sc::Dim::none},
  };
  for (const auto& [subject, dim] : table) {
    SCOPED_TRACE(subject);
    ASSERT_TRUE(sc::subject_dim(subject).has_value());
    EXPECT_EQ(*sc::subject_dim(subject), dim);
  }
}

TEST(dds_scenario_errors, EveryVerbParsesAndRoundTrips) {
  const auto s = sc::parse(
      "scenario every-verb_1\r\n"
      "title \"back\\\\slash\"\n"
      "duration\t2 min\n"
      "boards 3\n"
      "timing realtime\n"
      "period 50 ms\n"
      "seed 7\n"
      "baud 9600\n"
      "board battery 3.7 V\n"
      "board charger plugged\n"
      "board usb unplugged\n"
      "board temperature 25 degC\n"
      "board pos y -1.5 cm\n"
      "board endstop x max 0.2 m\n"
      "board param microsteps 16\n"
      "board param accel 5 mm/s2\n"
      "board fram accel 10000\n"
      "fault delay 20 ms\n"
      "fault duplicate 1 % to_board from 1 s\n"
      "fault reorder 2 % both\n"
      "fault corrupt 3 % to_pc from 1 s to 1 min\n"
      "at 0 s @all subscribe all\n"
      "at 0 s @2 unsubscribe rotation\n"
      "at 1e3 ms usb plug#comment\n"
      "at +2E+2 ms temperature -5 degC\n"
      "at 2 s rotate 90 deg\n"
      "at 2 s link cut\n"
      "at 3 s link restore\n"
      "at 3 s peripherals off\n"
      "at 4 s endstop y min on\n"
      "at 4 s button hold\n"
      "at 4 s tmc y TPOWER_DOWN 10\n"
      "at 5 s set speed slow 5e-1 mm/s\n"
      "at 5 s move x +5 mm\n"
      "at 5 s goto y 1 um\n"
      "at 5 s home y\n"
      "at 5 s reboot\n"
      "at 5 s charger unplug\n"
      "at 5 s ble standby\n"
      "expect at 1 s board.charge_current > 100 mA ± 5 mA\n"
      "expect by 2 s board.temperature >= 20 degC +- 1 degC\n"
      "expect always board.rotation != 0 mdeg\n"
      "expect from 0 s to 1 min board.battery < 4.2 V\n"
      "expect end @1 y.blocked == off\n"
      "expect end tmc.y.TPOWER_DOWN == 10\n"
      "expect end tmc.x.s2ga == off\n"
      "expect end x.dir != +\n"
      "expect end echo.last == ok.x\n"
      "expect end sub.battery == 3700",   // no final newline
      "v.scn");
  EXPECT_EQ(s.name, "every-verb_1");
  EXPECT_EQ(s.title, "back\\slash");
  EXPECT_EQ(s.duration_us, 120'000'000);
  EXPECT_EQ(s.boards, 3U);
  EXPECT_EQ(s.timing, sc::Timing::realtime);
  EXPECT_EQ(s.period_us, 50'000);
  EXPECT_EQ(s.seed, 7U);
  EXPECT_EQ(s.baud, 9600U);

  ASSERT_EQ(s.setup.size(), 9U);
  EXPECT_EQ(*s.setup[0].amount, (sc::Quantity{3700.0, sc::Dim::voltage}));
  EXPECT_EQ(s.setup[1].word, "plugged");
  EXPECT_EQ(s.setup[2].key, "usb");
  EXPECT_EQ(s.setup[2].word, "unplugged");
  EXPECT_EQ(*s.setup[3].amount, (sc::Quantity{25000.0, sc::Dim::temperature}));
  EXPECT_EQ(s.setup[4].axis, 'y');
  EXPECT_EQ(*s.setup[4].amount, (sc::Quantity{-15000.0, sc::Dim::length}));
  EXPECT_EQ(s.setup[5].word, "max");
  EXPECT_EQ(*s.setup[5].amount, (sc::Quantity{200000.0, sc::Dim::length}));
  EXPECT_EQ(*s.setup[6].amount, (sc::Quantity{16.0, sc::Dim::none}));
  EXPECT_EQ(*s.setup[7].amount, (sc::Quantity{5000.0, sc::Dim::accel}));   // param keeps its unit
  EXPECT_EQ(s.setup[8].key, "fram");

  ASSERT_EQ(s.faults.size(), 4U);
  EXPECT_EQ(s.faults[0].kind, sc::FaultKind::delay);
  EXPECT_FALSE(s.faults[0].jitter.has_value());
  EXPECT_EQ(s.faults[1].kind, sc::FaultKind::duplicate);
  EXPECT_EQ(s.faults[1].dir, sc::Direction::to_board);
  EXPECT_EQ(s.faults[1].from_us, 1'000'000);
  EXPECT_FALSE(s.faults[1].to_us.has_value());
  EXPECT_EQ(s.faults[2].dir, sc::Direction::both);
  EXPECT_EQ(*s.faults[3].to_us, 60'000'000);

  ASSERT_EQ(s.actions.size(), 18U);
  EXPECT_TRUE(s.actions[0].target.all);
  EXPECT_EQ(s.actions[0].verb, sc::Verb::subscribe);
  EXPECT_EQ(s.actions[0].word, "all");
  EXPECT_FALSE(s.actions[1].target.all);
  EXPECT_EQ(s.actions[1].target.board, 2U);
  EXPECT_EQ(s.actions[1].verb, sc::Verb::unsubscribe);
  EXPECT_EQ(s.actions[2].t_us, 1'000'000);    // 1e3 ms
  EXPECT_EQ(s.actions[2].verb, sc::Verb::usb);
  EXPECT_EQ(s.actions[2].word, "plug");
  EXPECT_EQ(s.actions[3].t_us, 1'200'000);    // +2E+2 ms after the previous 'at'
  EXPECT_EQ(*s.actions[3].amount, (sc::Quantity{-5000.0, sc::Dim::temperature}));
  EXPECT_EQ(*s.actions[4].amount, (sc::Quantity{90000.0, sc::Dim::angle}));
  EXPECT_EQ(s.actions[5].verb, sc::Verb::link_cut);
  EXPECT_FALSE(s.actions[5].amount.has_value());   // until restored
  EXPECT_EQ(s.actions[6].verb, sc::Verb::link_restore);
  EXPECT_EQ(s.actions[7].verb, sc::Verb::peripherals);
  EXPECT_EQ(s.actions[8].verb, sc::Verb::endstop);
  EXPECT_EQ(s.actions[8].word, "min");
  EXPECT_EQ(s.actions[8].word2, "on");
  EXPECT_EQ(s.actions[9].verb, sc::Verb::button);
  EXPECT_EQ(s.actions[10].word, "TPOWER_DOWN");
  EXPECT_EQ(*s.actions[11].amount, (sc::Quantity{500.0, sc::Dim::speed}));
  EXPECT_EQ(*s.actions[12].amount, (sc::Quantity{5000.0, sc::Dim::length}));

  ASSERT_EQ(s.expectations.size(), 10U);
  EXPECT_EQ(*s.expectations[0].tol, (sc::Quantity{5.0, sc::Dim::current}));
  EXPECT_EQ(*s.expectations[1].tol, (sc::Quantity{1000.0, sc::Dim::temperature}));
  EXPECT_EQ(s.expectations[3].t2_us, 60'000'000);
  EXPECT_EQ(s.expectations[4].target.board, 1U);
  EXPECT_EQ(std::get<std::string>(s.expectations[8].value), "ok.x");
  EXPECT_EQ(s.expectations[9].line, 49);

  for (const sc::Action& a : s.actions) EXPECT_NE(sc::to_string(a.verb), "?");
  const std::string text = sc::to_text(s);
  EXPECT_NE(text.find("timing realtime"), std::string::npos) << text;
  EXPECT_NE(text.find("title \"back\\\\slash\""), std::string::npos) << text;
  EXPECT_NE(text.find("fault duplicate 1 % to_board from 1 s\n"), std::string::npos) << text;
  EXPECT_NE(text.find("fault corrupt 3 % to_pc from 1 s to 60 s\n"), std::string::npos) << text;
  EXPECT_EQ(round_trip(s), without_lines(s)) << text;
}

TEST(dds_scenario_errors, FaultWindowAndJitterRoundTrip) {
  const auto s = sc::parse(kHead + "fault delay 20 ms jitter 5 ms to_pc to_board from 0 s to 2 s\n"
                                   "fault drop 5 % from 0 s to 10 s\n",
                           "t.scn");
  ASSERT_EQ(s.faults.size(), 2U);
  EXPECT_EQ(s.faults[0].dir, sc::Direction::to_board);   // the last direction given wins
  EXPECT_EQ(*s.faults[0].jitter, (sc::Quantity{5000.0, sc::Dim::time}));
  EXPECT_EQ(s.faults[1].from_us, 0);
  EXPECT_EQ(*s.faults[1].to_us, 10'000'000);
  const std::string text = sc::to_text(s);
  EXPECT_NE(text.find("fault delay 20000 us jitter 5000 us to_board from 0 s to 2 s\n"),
            std::string::npos)
      << text;
  EXPECT_EQ(round_trip(s), without_lines(s)) << text;
}

// The printer writes any finite quantity in full: the largest and the smallest normal doubles
// read back unchanged (a fixed notation of 1e308 is 309 digits long).
TEST(dds_scenario_errors, ExtremeQuantitiesRoundTrip) {
  const auto s = sc::parse(kHead + "board temperature -1.7e308 mdegC\nboard param lead 2.2250738585072014e-308 um\n"
                                   "at 1 s battery 1e70 V\nexpect end x.pos < 1e-300 um tol 1e300 um\n",
                           "t.scn");
  ASSERT_EQ(s.setup.size(), 2U);
  EXPECT_EQ(s.setup[0].amount->value, -1.7e308);
  EXPECT_EQ(s.setup[1].amount->value, 2.2250738585072014e-308);
  EXPECT_EQ(s.actions[0].amount->value, 1e70 * 1e3);  // V to mV
  const std::string text = sc::to_text(s);
  EXPECT_NE(text.find("board temperature -16999999999999999"), std::string::npos) << text;  // 309 digits
  EXPECT_EQ(round_trip(s), without_lines(s)) << text;
}

TEST(dds_scenario_errors, UnitNames) {
  EXPECT_EQ(sc::unit_name(sc::Dim::none), "");
  EXPECT_EQ(sc::unit_name(sc::Dim::length), "um");
  EXPECT_EQ(sc::unit_name(sc::Dim::speed), "um/s");
  EXPECT_EQ(sc::unit_name(sc::Dim::accel), "um/s2");
  EXPECT_EQ(sc::unit_name(sc::Dim::time), "us");
  EXPECT_EQ(sc::unit_name(sc::Dim::voltage), "mV");
  EXPECT_EQ(sc::unit_name(sc::Dim::current), "mA");
  EXPECT_EQ(sc::unit_name(sc::Dim::temperature), "mdegC");
  EXPECT_EQ(sc::unit_name(sc::Dim::angle), "mdeg");
  EXPECT_EQ(sc::unit_name(sc::Dim::ratio), "%");
  // Bytes outside the enums (hand-built values): neutral placeholders, never a table overrun.
  EXPECT_EQ(sc::unit_name(static_cast<sc::Dim>(200)), "");
  EXPECT_EQ(sc::to_string(sc::Verb::raw), "raw");
  EXPECT_EQ(sc::to_string(static_cast<sc::Verb>(200)), "?");
}

TEST(dds_scenario_errors, HoldsEveryOperator) {
  sc::Expectation e;
  e.subject = "x.pos";
  e.value = sc::Quantity{100.0, sc::Dim::length};
  const auto um = [](double v) { return sc::Value{sc::Quantity{v, sc::Dim::length}}; };
  struct Row {
    sc::Op op;
    double actual;
    bool without_tol;
    bool with_tol;   // tol 2 um
  };
  const std::vector<Row> rows{
      {sc::Op::Eq, 101.0, false, true}, {sc::Op::Eq, 100.0, true, true},  {sc::Op::Eq, 103.0, false, false},
      {sc::Op::Ne, 101.0, true, false}, {sc::Op::Ne, 100.0, false, false}, {sc::Op::Ne, 103.0, true, true},
      {sc::Op::Lt, 100.0, false, true}, {sc::Op::Lt, 99.0, true, true},    {sc::Op::Lt, 102.0, false, false},
      {sc::Op::Le, 100.0, true, true},  {sc::Op::Le, 101.0, false, true},  {sc::Op::Le, 102.5, false, false},
      {sc::Op::Gt, 100.0, false, true}, {sc::Op::Gt, 101.0, true, true},   {sc::Op::Gt, 98.0, false, false},
      {sc::Op::Ge, 100.0, true, true},  {sc::Op::Ge, 99.0, false, true},   {sc::Op::Ge, 97.5, false, false},
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(testing::Message() << "op " << static_cast<int>(r.op) << " actual " << r.actual);
    e.op = r.op;
    e.tol.reset();
    EXPECT_EQ(sc::holds(e, um(r.actual)), r.without_tol);
    e.tol = sc::Quantity{2.0, sc::Dim::length};
    EXPECT_EQ(sc::holds(e, um(r.actual)), r.with_tol);
  }
  EXPECT_THROW((void)sc::holds(e, sc::Value{std::string("reached")}), std::invalid_argument);

  sc::Expectation w;
  w.subject = "x.status";
  w.value = std::string("reached");
  w.op = sc::Op::Lt;   // only a hand-built expectation can carry this (parse() rejects it)
  EXPECT_THROW((void)sc::holds(w, sc::Value{std::string("reached")}), std::invalid_argument);
  w.op = sc::Op::Ne;
  EXPECT_FALSE(sc::holds(w, sc::Value{std::string("reached")}));
  EXPECT_TRUE(sc::holds(w, sc::Value{std::string("idle")}));
}

// The round-trip property (parse(to_text(s)) == s) is only as strong as operator==: a field the
// comparison skipped would make it vacuous for that field. Each field alone must break equality.
TEST(dds_scenario_errors, EqualityDistinguishesEveryField) {
  const sc::Quantity q{1.0, sc::Dim::length};
  EXPECT_EQ(q, (sc::Quantity{1.0, sc::Dim::length}));
  EXPECT_NE(q, (sc::Quantity{2.0, sc::Dim::length}));
  EXPECT_NE(q, (sc::Quantity{1.0, sc::Dim::speed}));

  const sc::Target t{false, 1};
  EXPECT_NE(t, (sc::Target{true, 1}));
  EXPECT_NE(t, (sc::Target{false, 2}));

  sc::Action a;
  a.t_us = 5;
  a.target = t;
  a.verb = sc::Verb::jog;
  a.axis = 'x';
  a.word = "+";
  a.word2 = "fast";
  a.amount = q;
  a.line = 3;
  const std::vector<void (*)(sc::Action&)> action_edits{
      [](sc::Action& x) { x.t_us = 6; },         [](sc::Action& x) { x.target.board = 0; },
      [](sc::Action& x) { x.verb = sc::Verb::stop; }, [](sc::Action& x) { x.axis = 'y'; },
      [](sc::Action& x) { x.word = "-"; },       [](sc::Action& x) { x.word2 = "slow"; },
      [](sc::Action& x) { x.amount.reset(); },   [](sc::Action& x) { x.line = 4; },
  };
  for (std::size_t i = 0; i < action_edits.size(); ++i) {
    sc::Action b = a;
    EXPECT_EQ(b, a);
    action_edits[i](b);
    EXPECT_NE(b, a) << "action field " << i;
  }

  sc::Expectation e;
  e.when = sc::When::between;
  e.t_us = 1;
  e.t2_us = 2;
  e.target = t;
  e.subject = "x.pos";
  e.op = sc::Op::Le;
  e.value = q;
  e.tol = q;
  e.line = 9;
  const std::vector<void (*)(sc::Expectation&)> expectation_edits{
      [](sc::Expectation& x) { x.when = sc::When::at; },    [](sc::Expectation& x) { x.t_us = 0; },
      [](sc::Expectation& x) { x.t2_us = 3; },             [](sc::Expectation& x) { x.target.all = true; },
      [](sc::Expectation& x) { x.subject = "y.pos"; },     [](sc::Expectation& x) { x.op = sc::Op::Lt; },
      [](sc::Expectation& x) { x.value = std::string("reached"); },
      [](sc::Expectation& x) { x.tol.reset(); },           [](sc::Expectation& x) { x.line = 10; },
  };
  for (std::size_t i = 0; i < expectation_edits.size(); ++i) {
    sc::Expectation b = e;
    EXPECT_EQ(b, e);
    expectation_edits[i](b);
    EXPECT_NE(b, e) << "expectation field " << i;
  }

  sc::Fault f;
  f.kind = sc::FaultKind::delay;
  f.amount = sc::Quantity{20.0, sc::Dim::time};
  f.jitter = sc::Quantity{5.0, sc::Dim::time};
  f.dir = sc::Direction::to_pc;
  f.from_us = 1;
  f.to_us = 2;
  f.line = 7;
  const std::vector<void (*)(sc::Fault&)> fault_edits{
      [](sc::Fault& x) { x.kind = sc::FaultKind::drop; },   [](sc::Fault& x) { x.amount.value = 21.0; },
      [](sc::Fault& x) { x.jitter.reset(); },               [](sc::Fault& x) { x.dir = sc::Direction::both; },
      [](sc::Fault& x) { x.from_us = 0; },                  [](sc::Fault& x) { x.to_us.reset(); },
      [](sc::Fault& x) { x.line = 8; },
  };
  for (std::size_t i = 0; i < fault_edits.size(); ++i) {
    sc::Fault b = f;
    EXPECT_EQ(b, f);
    fault_edits[i](b);
    EXPECT_NE(b, f) << "fault field " << i;
  }

  sc::Setup st;
  st.key = "endstop";
  st.axis = 'x';
  st.word = "min";
  st.amount = q;
  st.line = 2;
  const std::vector<void (*)(sc::Setup&)> setup_edits{
      [](sc::Setup& x) { x.key = "pos"; },  [](sc::Setup& x) { x.axis = 'y'; },  [](sc::Setup& x) { x.word = "max"; },
      [](sc::Setup& x) { x.amount.reset(); }, [](sc::Setup& x) { x.line = 3; },
  };
  for (std::size_t i = 0; i < setup_edits.size(); ++i) {
    sc::Setup b = st;
    EXPECT_EQ(b, st);
    setup_edits[i](b);
    EXPECT_NE(b, st) << "setup field " << i;
  }

  sc::Scenario s;
  s.name = "n";
  s.title = "t";
  s.duration_us = 10;
  s.setup.push_back(st);
  s.faults.push_back(f);
  s.actions.push_back(a);
  s.expectations.push_back(e);
  const std::vector<void (*)(sc::Scenario&)> scenario_edits{
      [](sc::Scenario& x) { x.name = "m"; },          [](sc::Scenario& x) { x.title = "u"; },
      [](sc::Scenario& x) { x.boards = 2; },          [](sc::Scenario& x) { x.duration_us = 11; },
      [](sc::Scenario& x) { x.period_us = 1; },       [](sc::Scenario& x) { x.timing = sc::Timing::realtime; },
      [](sc::Scenario& x) { x.seed = 2; },            [](sc::Scenario& x) { x.baud = 9600; },
      [](sc::Scenario& x) { x.setup.clear(); },       [](sc::Scenario& x) { x.faults.clear(); },
      [](sc::Scenario& x) { x.actions.clear(); },     [](sc::Scenario& x) { x.expectations.clear(); },
      [](sc::Scenario& x) { x.setup[0].line = 99; },  [](sc::Scenario& x) { x.faults[0].line = 99; },
      [](sc::Scenario& x) { x.actions[0].line = 99; }, [](sc::Scenario& x) { x.expectations[0].line = 99; },
  };
  for (std::size_t i = 0; i < scenario_edits.size(); ++i) {
    sc::Scenario b = s;
    EXPECT_EQ(b, s);
    scenario_edits[i](b);
    EXPECT_NE(b, s) << "scenario field " << i;
  }
}
