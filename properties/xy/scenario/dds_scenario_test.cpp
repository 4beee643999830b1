// The scenario parser (pc/dds, ap_xy_scenario) and the bundled scenarios/ files.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "sim/xy/scenario.hpp"

namespace sc = ap::sim::xy::scenario;

namespace {

sc::Scenario without_lines(sc::Scenario s) {
  for (auto& a : s.actions) a.line = 0;
  for (auto& e : s.expectations) e.line = 0;
  for (auto& f : s.faults) f.line = 0;
  for (auto& st : s.setup) st.line = 0;
  return s;
}

std::string error_of(const std::string& text) {
  try {
    sc::parse(text, "t.scn");
  } catch (const sc::ParseError& e) {
    return e.what();
  }
  return "no error";
}

const std::string kHead = "scenario t\nduration 10 s\n";

}  // namespace

TEST(dds_scenario, BundledScenariosParseAndRoundTrip) {
  // The bundled scenarios (docs/scenarios.md); the link-fault regressions of docs/protocol.md
  // "Delivery" (scenarios/xy/regressions/, where shrunk storms join them).
  const std::set<std::string> expected{"absolute_20mm",  "manual_reversal", "accel_save_reboot",
                                       "ihold_irun",     "endstop_hit",     "battery_charger_blocking",
                                       "link_loss_jog",  "homing",          "faulty_link_jog",
                                       "many_boards",    "many_boards_faults", "gcode_thesis",
                                       "sensors",        "ble_led",         "homing_power_cycle",
                                       "positioning_slow", "shutdown_button",
                                       // docs/protocol.md "Delivery", rule 6: the board ahead of the client from the start
                                       "board_ahead_of_the_client"};
  const std::set<std::string> regressions{"link_all_faults", "link_corrupt_delay", "link_corrupt_drop",
                                          "link_corrupt_reorder", "link_drop_stop_lost",
                                          // docs/protocol.md "Delivery": a repeat tells the outcome its frame had
                                          "repeat_after_block_usb", "repeat_after_block_charger",
                                          "repeat_after_block_battery"};
  std::set<std::string> found, found_regressions;
  for (const char* dir : {"/scenarios/xy", "/scenarios/xy/regressions"}) {
    for (const auto& entry : std::filesystem::directory_iterator(std::string(AP_SOURCE_DIR) + dir)) {
      if (entry.path().extension() != ".scn") continue;
      SCOPED_TRACE(entry.path().string());
      const sc::Scenario s = sc::parse_file(entry.path().string());
      EXPECT_EQ(s.name, entry.path().stem().string()) << "the file name is the scenario name";
      EXPECT_FALSE(s.title.empty());
      EXPECT_FALSE(s.actions.empty());
      EXPECT_FALSE(s.expectations.empty());
      EXPECT_TRUE(std::is_sorted(s.actions.begin(), s.actions.end(),
                                 [](const auto& a, const auto& b) { return a.t_us < b.t_us; }));
      const sc::Scenario again = sc::parse(sc::to_text(s), "printed");
      EXPECT_EQ(without_lines(again), without_lines(s)) << sc::to_text(s);
      (std::string(dir) == "/scenarios/xy" ? found : found_regressions).insert(s.name);
    }
  }
  EXPECT_EQ(found, expected);
  for (const std::string& r : regressions) EXPECT_EQ(found_regressions.count(r), 1U) << r;
}

TEST(dds_scenario, UnitsAreCanonical) {
  const auto s = sc::parse(kHead +
                           "at 1.5 s goto x 20 mm\nat +500 ms set accel 5 mm/s^2\nat 2 s set speed fast 0.01 m/s\n"
                           "at 2 s battery 3.3 V\nat 3 s move y -250um\nfault drop 5 %\nfault delay 20 ms jitter 5 ms to_pc from 1 s to 2 s\n"
                           "expect at 4 s x.pos == 20 mm tol 1 um\nexpect always x.speed <= 10 mm/s\n"
                           "expect from 1 s to 2 s x.dir == +\nexpect end @0 gaps == 0\n",
                           "t.scn");
  ASSERT_EQ(s.actions.size(), 5U);
  EXPECT_EQ(s.actions[0].t_us, 1'500'000);
  EXPECT_EQ(s.actions[0].verb, sc::Verb::go_to);
  EXPECT_EQ(s.actions[0].axis, 'x');
  EXPECT_EQ(*s.actions[0].amount, (sc::Quantity{20000.0, sc::Dim::length}));
  EXPECT_EQ(s.actions[1].t_us, 2'000'000);   // relative to the previous 'at'
  EXPECT_EQ(*s.actions[1].amount, (sc::Quantity{5000.0, sc::Dim::accel}));
  EXPECT_EQ(s.actions[2].word, "fast");
  EXPECT_EQ(s.actions[2].amount->value, 10000.0);
  EXPECT_EQ(s.actions[3].amount->value, 3300.0);
  EXPECT_EQ(s.actions[4].amount->value, -250.0);
  ASSERT_EQ(s.faults.size(), 2U);
  EXPECT_EQ(s.faults[0].amount.value, 5.0);
  EXPECT_EQ(s.faults[1].kind, sc::FaultKind::delay);
  EXPECT_EQ(s.faults[1].dir, sc::Direction::to_pc);
  EXPECT_EQ(s.faults[1].jitter->value, 5000.0);
  EXPECT_EQ(*s.faults[1].to_us, 2'000'000);
  ASSERT_EQ(s.expectations.size(), 4U);
  EXPECT_EQ(s.expectations[0].tol->value, 1.0);
  EXPECT_EQ(s.expectations[1].when, sc::When::always);
  EXPECT_EQ(s.expectations[1].op, sc::Op::Le);
  EXPECT_EQ(std::get<std::string>(s.expectations[2].value), "+");
  EXPECT_EQ(s.expectations[2].t2_us, 2'000'000);
  EXPECT_FALSE(s.expectations[3].target.all);
}

TEST(dds_scenario, ErrorsNameTheLineAndTheProblem) {
  EXPECT_EQ(error_of("duration 1 s\n"), "t.scn:1: a scenario file starts with 'scenario NAME'");
  EXPECT_EQ(error_of("scenario t\n"), "t.scn:2: no 'duration'");
  EXPECT_EQ(error_of(kHead + "at 1 s fly x\n"), "t.scn:3: unknown action 'fly'");
  EXPECT_EQ(error_of(kHead + "at 1 s goto x 20 mm/s\n"),
            "t.scn:3: target position: expected a length (um, mm, ...), got a speed (um/s, mm/s, ...)");
  EXPECT_EQ(error_of(kHead + "at 1 s goto z 20 mm\n"), "t.scn:3: axis must be x or y, got 'z'");
  EXPECT_EQ(error_of(kHead + "at 1 s goto x 20\n"),
            "t.scn:3: target position: '20' needs a unit: a length (um, mm, ...)");
  EXPECT_EQ(error_of(kHead + "at 2 s stop x\nat 1 s stop x\n"),
            "t.scn:4: actions must be in time order (this one is before the previous 'at')");
  EXPECT_EQ(error_of(kHead + "at 11 s stop x\n"), "t.scn:3: action after the end of the run");
  EXPECT_EQ(error_of(kHead + "at 1 s @1 stop x\n"), "t.scn:3: board 1 does not exist (boards 1)");
  EXPECT_EQ(error_of(kHead + "expect at 1 s x.pos == reached\n"),
            "t.scn:3: subject x.pos needs a length (um, mm, ...)");
  EXPECT_EQ(error_of(kHead + "expect at 1 s x.status < idle\n"), "t.scn:3: words compare with == or != only");
  EXPECT_EQ(error_of(kHead + "expect at 1 s z.pos == 1 mm\n"), "t.scn:3: unknown subject 'z.pos'");
  EXPECT_EQ(error_of(kHead + "fault drop 150 %\n"), "t.scn:3: fault rate above 100 %");
  EXPECT_EQ(error_of(kHead + "at 1 s jog x +\nboards 4\n"), "t.scn:4: 'boards' must come before actions and expectations");
  EXPECT_EQ(error_of(kHead + "title \"open\n"), "t.scn:3: unterminated string");
  // A word left over: the shared kit's message (sim/scenario_text.hpp), the word and where.
  EXPECT_EQ(error_of(kHead + "at 1 s jog x + fast extra\n"), "t.scn:3: unexpected 'extra' at the end of the line");
  EXPECT_EQ(error_of(kHead + "expect at 1 s x.pos == 2 mm tol 1 mm/s\n"),
            "t.scn:3: tolerance: expected a length (um, mm, ...), got a speed (um/s, mm/s, ...)");
}

TEST(dds_scenario, CommentsBlankLinesAndQuotes) {
  const auto s = sc::parse("# header comment\n\nscenario q   # trailing\ntitle \"a \\\"quoted\\\" # title\"\n"
                           "duration 1 s\nat 0 s raw \"01000000 02000000\"\n",
                           "q.scn");
  EXPECT_EQ(s.title, "a \"quoted\" # title");
  ASSERT_EQ(s.actions.size(), 1U);
  EXPECT_EQ(s.actions[0].verb, sc::Verb::raw);
  EXPECT_EQ(s.actions[0].word, "01000000 02000000");
  EXPECT_EQ(without_lines(sc::parse(sc::to_text(s))), without_lines(s));
}

TEST(dds_scenario, HoldsAppliesOperatorAndTolerance) {
  const auto s = sc::parse(kHead +
                           "expect at 1 s x.pos == 20 mm tol 1 um\nexpect at 1 s x.speed <= 10 mm/s tol 0.05 mm/s\n"
                           "expect at 1 s x.status == reached\nexpect end gaps >= 15\nexpect at 1 s x.dir != +\n",
                           "t.scn");
  const auto um = [](double v) { return sc::Value{sc::Quantity{v, sc::Dim::length}}; };
  const auto ums = [](double v) { return sc::Value{sc::Quantity{v, sc::Dim::speed}}; };
  EXPECT_TRUE(sc::holds(s.expectations[0], um(20000.9)));
  EXPECT_FALSE(sc::holds(s.expectations[0], um(20001.5)));
  EXPECT_TRUE(sc::holds(s.expectations[1], ums(10049.0)));
  EXPECT_FALSE(sc::holds(s.expectations[1], ums(10051.0)));
  EXPECT_TRUE(sc::holds(s.expectations[2], sc::Value{std::string("reached")}));
  EXPECT_FALSE(sc::holds(s.expectations[2], sc::Value{std::string("decel")}));
  EXPECT_TRUE(sc::holds(s.expectations[3], sc::Value{sc::Quantity{15, sc::Dim::none}}));
  EXPECT_FALSE(sc::holds(s.expectations[3], sc::Value{sc::Quantity{14, sc::Dim::none}}));
  EXPECT_TRUE(sc::holds(s.expectations[4], sc::Value{std::string("-")}));
  EXPECT_THROW((void)sc::holds(s.expectations[0], ums(1.0)), std::invalid_argument);
  EXPECT_THROW((void)sc::holds(s.expectations[2], um(1.0)), std::invalid_argument);
}

// The runner judges with holds() too (sim/xy/src/pc.cpp), so what it adds lives here: `blocked`
// stands for every blocking status, and a value exactly on a bound after a unit conversion
// (0.1 + 0.2 is not 0.3 in binary) still holds.
TEST(dds_scenario, HoldsBlockedStatusAndBoundsAfterConversion) {
  const auto s = sc::parse(kHead +
                           "expect at 1 s x.status == blocked\nexpect at 1 s y.status != blocked\n"
                           "expect at 1 s board.state == blocked\nexpect at 1 s x.pos == 0.3 um\n"
                           "expect at 1 s x.pos <= 0.3 um\nexpect at 1 s x.pos >= 0.3 um\n",
                           "t.scn");
  const sc::Value blk_usb{std::string("blk_usb")};
  const sc::Value blk_charger{std::string("blk_charger")};
  EXPECT_TRUE(sc::holds(s.expectations[0], blk_usb));
  EXPECT_TRUE(sc::holds(s.expectations[0], blk_charger));
  EXPECT_FALSE(sc::holds(s.expectations[0], sc::Value{std::string("reached")}));
  EXPECT_FALSE(sc::holds(s.expectations[1], blk_usb));
  EXPECT_TRUE(sc::holds(s.expectations[1], sc::Value{std::string("idle")}));
  // Only an axis status widens `blocked`: board.state names its own state.
  EXPECT_FALSE(sc::holds(s.expectations[2], blk_usb));
  EXPECT_TRUE(sc::holds(s.expectations[2], sc::Value{std::string("blocked")}));
  const sc::Value sum{sc::Quantity{0.1 + 0.2, sc::Dim::length}};  // 0.30000000000000004
  EXPECT_TRUE(sc::holds(s.expectations[3], sum));
  EXPECT_TRUE(sc::holds(s.expectations[4], sum));
  EXPECT_TRUE(sc::holds(s.expectations[5], sc::Value{sc::Quantity{0.3 - 1e-12, sc::Dim::length}}));
  EXPECT_FALSE(sc::holds(s.expectations[3], sc::Value{sc::Quantity{0.31, sc::Dim::length}}));
}

// Random scenarios survive print -> parse unchanged.
RC_GTEST_PROP(dds_scenario, PrintParseIsIdentity, ()) {
  sc::Scenario s;
  s.name = "gen";
  s.boards = *rc::gen::inRange<std::uint32_t>(1, 33);
  s.duration_us = *rc::gen::inRange<std::int64_t>(1, 100'000) * 1000;
  s.seed = *rc::gen::inRange<std::uint64_t>(0, 1000);
  const auto n = *rc::gen::inRange<int>(0, 20);
  std::int64_t t = 0;
  for (int i = 0; i < n; ++i) {
    t = std::min(s.duration_us, t + *rc::gen::inRange<std::int64_t>(0, 5000) * 1000);
    sc::Action a;
    a.t_us = t;
    a.verb = *rc::gen::element(sc::Verb::go_to, sc::Verb::move, sc::Verb::stop, sc::Verb::jog, sc::Verb::set_accel,
                               sc::Verb::battery, sc::Verb::save, sc::Verb::tmc);
    const bool one = *rc::gen::arbitrary<bool>();
    a.target = sc::Target{!one, one ? *rc::gen::inRange<std::uint32_t>(0, s.boards) : 0U};
    const double um = static_cast<double>(*rc::gen::inRange(-200000, 200000)) / 4.0;
    switch (a.verb) {
      case sc::Verb::go_to:
      case sc::Verb::move: a.axis = 'x'; a.amount = sc::Quantity{um, sc::Dim::length}; break;
      case sc::Verb::stop: a.axis = 'y'; break;
      case sc::Verb::jog: a.axis = 'x'; a.word = "-"; a.word2 = *rc::gen::element<std::string>("", "slow"); break;
      case sc::Verb::set_accel: a.amount = sc::Quantity{std::abs(um), sc::Dim::accel}; break;
      case sc::Verb::battery: a.amount = sc::Quantity{std::abs(um), sc::Dim::voltage}; break;
      case sc::Verb::tmc: a.axis = 'y'; a.word = "IRUN"; a.amount = sc::Quantity{std::abs(std::floor(um)), sc::Dim::none}; break;
      default: break;
    }
    s.actions.push_back(a);
  }
  for (int i = 0; i < n; ++i) {
    sc::Expectation e;
    e.when = *rc::gen::element(sc::When::at, sc::When::always, sc::When::between, sc::When::by, sc::When::end);
    if (e.when == sc::When::at || e.when == sc::When::by || e.when == sc::When::between) {
      e.t_us = *rc::gen::inRange<std::int64_t>(0, s.duration_us / 1000 + 1) * 1000;
    }
    if (e.when == sc::When::between) e.t2_us = s.duration_us;
    e.subject = *rc::gen::element<std::string>("x.pos", "y.speed", "x.status", "gaps");
    const auto dim = *sc::subject_dim(e.subject);
    if (e.subject == "x.status") {
      e.value = std::string("reached");
    } else {
      e.op = *rc::gen::element(sc::Op::Eq, sc::Op::Ne, sc::Op::Lt, sc::Op::Le, sc::Op::Gt, sc::Op::Ge);
      e.value = sc::Quantity{static_cast<double>(*rc::gen::inRange(0, 1000000)) / 8.0, dim};
      if (*rc::gen::arbitrary<bool>()) e.tol = sc::Quantity{0.5, dim};
    }
    s.expectations.push_back(e);
  }
  const sc::Scenario back = without_lines(sc::parse(sc::to_text(s), "gen"));
  RC_ASSERT(back == s);
}
