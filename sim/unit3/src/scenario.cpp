// The unit3 scenario language (sim/unit3/scenario.hpp, docs/unit3-sim.md): one statement per
// line, `#` starts a comment outside strings, every error names file:line.
#include "sim/unit3/scenario.hpp"

#include <algorithm>
#include <cctype>

namespace ap::sim::unit3 {

namespace {

using text::Line;

// The unit3 dialect (docs/unit3-sim.md): strings carry the line's control bytes (\r \n \t \xHH),
// a time may reach 10^12 us, and the report shows the line up to a " #" comment.
const text::Dialect kDialect = {
    .full_escapes = true, .name_at_end = false, .cut_blank_hash = true, .one_title = false, .time = {20, 1'000'000'000'000LL}};

}  // namespace

const char* quantity_name(Quantity q) {
  switch (q) {
    case Quantity::Pulses: return "pulses";
    case Quantity::Counter: return "counter";
    case Quantity::Entry: return "entry";
    case Quantity::Dir: return "dir";
    case Quantity::Running: return "running";
    case Quantity::Remaining: return "remaining";
    case Quantity::Mode: return "mode";
  }
  return "?";
}

bool parse_time(const std::string& number, const std::string& unit, std::int64_t& us) {
  return text::parse_time(number, unit, us, kDialect.time);
}

namespace {

std::int64_t integer(Line& l, const char* what) {
  const std::string w = l.word(what);
  std::size_t k = 0;
  if (!w.empty() && (w[0] == '-' || w[0] == '+')) k = 1;
  if (k == w.size() || w.find_first_not_of("0123456789", k) != std::string::npos || w.size() - k > 18) {
    l.fail(std::string("expected ") + what + " (an integer), got '" + w + "'");
  }
  return std::stoll(w);
}

std::uint8_t axis(Line& l) {
  const std::string w = l.word("an axis");
  if (w == "x" || w == "X") return 0;
  if (w == "y" || w == "Y") return 1;
  if (w == "z" || w == "Z") return 2;
  l.fail("unknown axis '" + w + "' (x, y or z)");
}

Quantity quantity(Line& l) {
  const std::string w = l.word("a quantity");
  for (const Quantity q : {Quantity::Pulses, Quantity::Counter, Quantity::Entry, Quantity::Dir, Quantity::Running,
                           Quantity::Remaining, Quantity::Mode}) {
    if (w == quantity_name(q)) return q;
  }
  l.fail("unknown quantity '" + w + "' (pulses counter entry dir running remaining mode)");
}

// The value of an At/Between expectation: an integer, or + / - for dir.
std::int64_t quantity_value(Line& l, Quantity q) {
  if (q == Quantity::Dir && (l.peek_is("+") || l.peek_is("-"))) return l.word("a direction") == "+" ? 1 : -1;
  return integer(l, "a value");
}

void parse_action(Line& l, Scenario& s, std::int64_t t) {
  Action a;
  a.t_us = t;
  a.line = l.number();
  const std::string verb = l.word("an action");
  if (verb == "send") {
    a.kind = ActionKind::Send;
    a.bytes = l.string("the bytes");
    if (a.bytes.empty()) l.fail("send of no bytes");
    if (l.peek_is("lose")) {
      l.word("lose");
      const std::int64_t k = integer(l, "the index of the lost byte");
      if (k < 0 || static_cast<std::size_t>(k) >= a.bytes.size()) {
        l.fail("lose " + std::to_string(k) + ": the string has bytes 0.." + std::to_string(a.bytes.size() - 1));
      }
      a.bytes.erase(static_cast<std::size_t>(k), 1);
    }
  } else if (verb == "joystick") {
    a.kind = ActionKind::Joystick;
    a.axis = axis(l);
    const std::int64_t v = integer(l, "an ADC value");
    if (v < 0 || v > 65535) l.fail("ADC value " + std::to_string(v) + " outside 0..65535");
    a.adc = static_cast<std::uint16_t>(v);
  } else if (verb == "endstop") {
    a.kind = ActionKind::Endstop;
    a.axis = axis(l);
    const std::string end = l.word("min or max");
    if (end != "min" && end != "max") l.fail("expected min or max, got '" + end + "'");
    a.max_end = end == "max";
    const std::string st = l.word("on or off");
    if (st != "on" && st != "off") l.fail("expected on or off, got '" + st + "'");
    a.on = st == "on";
  } else if (verb == "press") {
    a.kind = ActionKind::Press;
    a.button = l.word("a button");
    static const char* const kButtons[] = {"enter", "back", "up", "down", "left", "right"};
    if (std::find_if(std::begin(kButtons), std::end(kButtons), [&](const char* b) { return a.button == b; }) ==
        std::end(kButtons)) {
      l.fail("unknown button '" + a.button + "' (enter back up down left right)");
    }
    if (!l.done()) {
      const std::string n = l.word("xN");
      if (n.size() < 2 || n[0] != 'x' || n.find_first_not_of("0123456789", 1) != std::string::npos || n.size() > 4) {
        l.fail("expected a repeat count xN, got '" + n + "'");
      }
      a.times = static_cast<std::uint32_t>(std::stoul(n.substr(1)));
      if (a.times == 0) l.fail("x0 presses nothing");
    }
  } else if (verb == "power-cycle") {
    a.kind = ActionKind::PowerCycle;
  } else {
    l.fail("unknown action '" + verb + "' (send joystick endstop press power-cycle)");
  }
  l.end();
  s.actions.push_back(std::move(a));
}

// After `expect`: the rest of the line. `end` stands for the duration, known only at the end
// of the file: kEnd marks it until then.
constexpr std::int64_t kEnd = -1;

void parse_expect(Line& l, Scenario& s, const std::string& text) {
  Expectation e;
  e.line = l.number();
  e.text = text;
  e.t_us = kEnd;
  const auto time_or_end = [&]() -> std::int64_t {
    if (l.peek_is("end")) {
      l.word("end");
      return kEnd;
    }
    return l.time();
  };
  bool by = false;
  if (l.peek_is("by")) {
    l.word("by");
    e.t_us = l.time();
    by = true;
  }
  const std::string w = l.word("an expectation");
  if (w == "at" || w == "between") {
    if (by) l.fail("'by' goes with replies, reports and settings; use 'at T' for the board's state");
    if (w == "between") {
      e.kind = ExpectKind::Between;
      e.t0_us = l.time();
      l.expect_word("and");
    } else {
      e.kind = ExpectKind::At;
    }
    e.t_us = time_or_end();
    e.quantity = quantity(l);
    e.axis = axis(l);
    e.op = l.op();
    e.value = quantity_value(l, e.quantity);
    if (e.kind == ExpectKind::Between && e.t_us != kEnd && e.t_us <= e.t0_us) l.fail("between T1 and T2 needs T1 < T2");
  } else if (w == "end") {
    // "expect end pulses y == 500": the same as "expect at end ...".
    if (by) l.fail("'by' and 'end' together");
    e.kind = ExpectKind::At;
    e.quantity = quantity(l);
    e.axis = axis(l);
    e.op = l.op();
    e.value = quantity_value(l, e.quantity);
  } else if (w == "report") {
    e.kind = ExpectKind::Report;
    e.axis = axis(l);
    e.op = l.op();
    if (l.peek_is("counter")) {
      l.word("counter");
      e.value_is_counter = true;
    } else {
      e.value = integer(l, "a counter value");
    }
  } else if (w == "replies") {
    e.kind = ExpectKind::Replies;
    e.bytes = l.string("the reply");
    e.op = l.op();
    e.value = integer(l, "a count");
  } else if (w == "reply") {
    e.kind = ExpectKind::Replies;
    e.bytes = l.string("the reply");
    e.op = Op::Ge;
    e.value = 1;
  } else if (w == "no") {
    const std::string what = l.word("reply or errors");
    if (what == "reply") {
      e.kind = ExpectKind::Replies;
      e.bytes = l.string("the reply");
      e.op = Op::Eq;
      e.value = 0;
    } else if (what == "errors") {
      e.kind = ExpectKind::NoErrors;
    } else {
      l.fail("expected 'no reply \"...\"' or 'no errors', got 'no " + what + "'");
    }
  } else if (w == "settings") {
    e.kind = ExpectKind::Settings;
    e.bytes = l.string("the settings");
    if (e.bytes.size() != 10 || e.bytes[0] != 'M' || e.bytes[4] != ';' || e.bytes[5] != 'T' || e.bytes[9] != ';') {
      l.fail("settings are written \"M<d><d><d>;T<d><d><d>;\"");
    }
  } else {
    l.fail("unknown expectation '" + w + "' (report replies reply no settings at between end)");
  }
  if (e.kind == ExpectKind::Replies && e.bytes.empty()) l.fail("an empty reply never arrives");
  if ((e.kind == ExpectKind::Replies) && e.value < 0) l.fail("a count of replies is never negative");
  l.end();
  s.expectations.push_back(std::move(e));
}

}  // namespace

Scenario parse(const std::string& text, const std::string& file) {
  Scenario s;
  s.file = file;
  text::Header head;
  bool have_eeprom = false;
  const int n = text::each_statement(text, file, kDialect, [&](Line& l, const std::string& shown) {
    const std::string kw = l.word("a statement");
    if (head.read(kw, l)) return;
    if (kw == "eeprom") {
      if (have_eeprom) l.fail("a second 'eeprom' line");
      const std::string w = l.word("default or blank");
      if (w == "default") s.eeprom = Eeprom::Default;
      else if (w == "blank") s.eeprom = Eeprom::Blank;
      else l.fail("eeprom '" + w + "': default or blank");
      have_eeprom = true;
      l.end();
    } else if (kw == "at") {
      const std::int64_t t = l.time();
      parse_action(l, s, t);
    } else if (kw == "expect") {
      parse_expect(l, s, shown);
    } else {
      l.fail("unknown statement '" + kw + "' (scenario title duration eeprom at expect)");
    }
  });
  head.check(file, n);
  s.name = head.name;
  s.title = head.title;
  s.duration_us = head.duration_us;
  for (const Action& a : s.actions) {
    if (a.t_us >= s.duration_us) throw ParseError(file, a.line, "action at or after the end of the run");
  }
  for (Expectation& e : s.expectations) {
    if (e.t_us == kEnd) e.t_us = s.duration_us;
    if (e.t_us > s.duration_us || e.t0_us > s.duration_us) {
      throw ParseError(file, e.line, "expectation after the end of the run");
    }
    if (e.kind == ExpectKind::Between && e.t0_us >= e.t_us) throw ParseError(file, e.line, "between T1 and T2 needs T1 < T2");
  }
  std::stable_sort(s.actions.begin(), s.actions.end(), [](const Action& a, const Action& b) { return a.t_us < b.t_us; });
  return s;
}

Scenario parse_file(const std::string& path) { return parse(text::read_file(path), path); }

}  // namespace ap::sim::unit3
