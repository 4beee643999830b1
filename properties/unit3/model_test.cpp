// Stateful test: the unit's firmware (core/unit3/board) against the reference model of what
// the PC sees (models/unit3, docs/unit3.md "Reference model"). Random interleavings of PC
// lines (good ones, and ones with a byte lost, changed or added), stick positions, endstops,
// buttons, time and power cycles; after every step the PC's bytes must be exactly the model's
// replies, each counter report must carry the model's count, and the pins must be pulses the
// model allows.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/unit3/board/unit.hpp"
#include "models/unit3/pc_view.hpp"
#include "sim/unit3/replies.hpp"

namespace {

namespace u = ap::unit3_board;
using ap::model::unit3::PcView;
using ap::sim::unit3::split_replies;

struct Sut {
  std::array<std::uint8_t, 8> eeprom{};
  std::unique_ptr<u::Unit> unit;
  u::Inputs in{};
  std::uint8_t seen_endstops = 0;  // what the unit read in its last tick
  Sut() {
    eeprom.fill(0xFF);
    unit = std::make_unique<u::Unit>(eeprom);
  }
  std::string take() { return ap::sim::unit3::take_all(*unit); }
};

std::string good_line() {
  const auto axis = *rc::gen::element('X', 'Y', 'Z');
  const auto mode_digits = *rc::gen::container<std::string>(3, rc::gen::element('0', '1', '2', '3', '4', '5'));
  const auto thread_digits = *rc::gen::container<std::string>(3, rc::gen::element('0', '1', '2', '3', '4', '5', '6'));
  const auto signs = *rc::gen::container<std::string>(3, rc::gen::element('+', '-'));
  // Counts: whole pulses in most modes, some not, and a few long ones.
  const auto count = *rc::gen::oneOf(rc::gen::element<std::uint64_t>(0, 1, 32, 64, 96, 320, 500, 3200, 16000),
                                     rc::gen::inRange<std::uint64_t>(0, 4000));
  char digits[32];
  std::snprintf(digits, sizeof digits, "%015llu", static_cast<unsigned long long>(count));
  switch (*rc::gen::inRange(0, 6)) {
    case 0: return "D" + signs + ";";
    case 1: return "M" + mode_digits + ";";
    case 2: return "T" + thread_digits + ";";
    case 3: return *rc::gen::element<std::string>("C;", "G;");
    default: return std::string(1, axis) + digits + ";";
  }
}

std::string damaged(std::string l) {
  const auto at = *rc::gen::inRange<std::size_t>(0, l.size());
  switch (*rc::gen::inRange(0, 3)) {
    case 0: l.erase(at, 1); break;  // a byte lost at 19200 baud
    case 1: l[at] = *rc::gen::element('a', '9', '7', '-', '+', 'Q', 'x', ' '); break;
    default: l.insert(at, 1, *rc::gen::element('0', '5', '+', ';')); break;
  }
  return l;
}

RC_GTEST_PROP(Unit3ModelProps, ThePcSeesWhatTheModelSays, ()) {
  Sut s;
  PcView m;
  const auto steps = *rc::gen::inRange(1, 60);
  for (int i = 0; i < steps; ++i) {
    std::vector<std::string> want;
    std::string got;
    switch (*rc::gen::inRange(0, 8)) {
      case 0:
      case 1: {
        const std::string l = *rc::gen::inRange(0, 4) == 0 ? damaged(good_line()) : good_line();
        for (const char c : l) s.unit->receive(static_cast<std::uint8_t>(c));
        want = m.receive(l, s.seen_endstops);
        got = s.take();
        RC_ASSERT(split_replies(got) == want);
        break;
      }
      case 2: s.in.adc[*rc::gen::inRange<std::size_t>(0, 3)] = *rc::gen::element<std::uint16_t>(0, 100, 499, 500, 512, 524, 525, 900, 1023); break;
      case 3: s.in.endstops = *rc::gen::element<std::uint8_t>(0, 0, 0, 1, 2, 4, 8, 16, 32, 63); break;
      case 4: {
        const int b = *rc::gen::inRange(0, 6);
        s.unit->press(static_cast<ap::unit3_menu::Button>(b));
        want = m.press(b);
        got = s.take();
        RC_ASSERT(split_replies(got) == want);
        break;
      }
      case 5:
        if (*rc::gen::inRange(0, 4) == 0) {
          s.unit = std::make_unique<u::Unit>(s.eeprom);
          s.seen_endstops = 0;
          m.power_cycle();
          break;
        }
        [[fallthrough]];
      default: {
        const int ms = *rc::gen::inRange(1, 1500);
        for (int t = 0; t < ms; ++t) {
          s.unit->tick(s.in);
          s.seen_endstops = s.in.endstops;
          ap::model::unit3::Pins p;
          for (std::size_t a = 0; a < 3; ++a) {
            p.pulses[a] = s.unit->out(a).pulses;
            p.dir[a] = s.unit->out(a).dir;
            p.running[a] = s.unit->out(a).running;
          }
          std::vector<int> stopped, cut;
          std::string why;
          const bool ok = m.tick(p, s.in.endstops, stopped, cut, why);
          RC_ASSERT_FALSE(why.size() > 0 && !ok && (RC_LOG() << why << " at tick " << t, true));
          // Replies of a tick: counter reports with the model's count, E23 exactly for a cut
          // move, and a report of every axis whose move ended or was cut.
          std::vector<int> reported;
          int e23 = 0;
          for (const auto& r : split_replies(s.take())) {
            if (r == "E23;") {
              ++e23;
              continue;
            }
            RC_ASSERT(r.size() == 21U);
            const int a = r[0] - 'X';
            RC_ASSERT(a >= 0 && a < 3);
            RC_ASSERT(r == PcView::report(a, m.counter(a)));
            reported.push_back(a);
          }
          RC_ASSERT(e23 == static_cast<int>(cut.size()));
          for (const int a : stopped) RC_ASSERT(std::count(reported.begin(), reported.end(), a) >= 1);
          for (const int a : cut) RC_ASSERT(std::count(reported.begin(), reported.end(), a) >= 1);
        }
        break;
      }
    }
  }
}

}  // namespace
