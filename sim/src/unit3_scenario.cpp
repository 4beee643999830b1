// The unit3 scenario language (sim/unit3_scenario.hpp, docs/unit3-sim.md): one statement per
// line, `#` starts a comment outside strings, every error names file:line.
#include "sim/unit3_scenario.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace ap::sim::unit3 {

bool compare(std::int64_t got, Op op, std::int64_t want) {
  switch (op) {
    case Op::Eq: return got == want;
    case Op::Ne: return got != want;
    case Op::Lt: return got < want;
    case Op::Le: return got <= want;
    case Op::Gt: return got > want;
    case Op::Ge: return got >= want;
  }
  return false;
}

const char* op_text(Op op) {
  switch (op) {
    case Op::Eq: return "==";
    case Op::Ne: return "!=";
    case Op::Lt: return "<";
    case Op::Le: return "<=";
    case Op::Gt: return ">";
    case Op::Ge: return ">=";
  }
  return "?";
}

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
  double scale = 0;
  if (unit == "s") scale = 1e6;
  else if (unit == "ms") scale = 1e3;
  else if (unit == "us") scale = 1;
  else return false;
  if (number.find_first_of("0123456789") == std::string::npos || number.size() > 20) return false;
  bool dot = false;
  for (const char c : number) {
    if (c == '.' && !dot) {
      dot = true;
    } else if (std::isdigit(static_cast<unsigned char>(c)) == 0) {
      return false;
    }
  }
  const double v = std::stod(number) * scale;
  if (v > 1e12) return false;  // 11 days of virtual time: a typo, not a scenario
  const double r = std::round(v);
  if (std::fabs(v - r) > 1e-6) return false;  // finer than 1 us
  us = static_cast<std::int64_t>(r);
  return true;
}

namespace {

struct Token {
  std::string text;
  bool quoted = false;
};

class Line {
 public:
  Line(std::string file, int n, std::vector<Token> t) : file_(std::move(file)), n_(n), t_(std::move(t)) {}

  [[noreturn]] void fail(const std::string& what) const { throw ParseError(file_, n_, what); }
  bool done() const { return i_ >= t_.size(); }
  const Token& peek() const {
    if (done()) fail("unexpected end of line");
    return t_[i_];
  }
  bool peek_is(const char* w) const { return !done() && !t_[i_].quoted && t_[i_].text == w; }
  std::string word(const char* what) {
    const Token& t = peek();
    if (t.quoted) fail(std::string("expected ") + what + ", got a string");
    ++i_;
    return t.text;
  }
  void expect_word(const char* w) {
    const std::string got = word(w);
    if (got != w) fail(std::string("expected '") + w + "', got '" + got + "'");
  }
  std::string string(const char* what) {
    const Token& t = peek();
    if (!t.quoted) fail(std::string("expected ") + what + " as a \"string\", got '" + t.text + "'");
    ++i_;
    return t.text;
  }
  // A time: "10 ms", "0.5 s" (also written together, "10ms").
  std::int64_t time() {
    std::string num = word("a time");
    std::string unit;
    const auto split = num.find_first_not_of("0123456789.");
    if (split != std::string::npos && split > 0) {
      unit = num.substr(split);
      num.resize(split);
    } else {
      if (done()) fail("time '" + num + "' needs a unit (s, ms, us)");
      unit = word("a time unit");
    }
    std::int64_t us = 0;
    if (!parse_time(num, unit, us)) fail("bad time '" + num + " " + unit + "' (a number and s, ms or us, whole us)");
    return us;
  }
  std::int64_t integer(const char* what) {
    const std::string w = word(what);
    std::size_t k = 0;
    if (!w.empty() && (w[0] == '-' || w[0] == '+')) k = 1;
    if (k == w.size() || w.find_first_not_of("0123456789", k) != std::string::npos || w.size() - k > 18) {
      fail(std::string("expected ") + what + " (an integer), got '" + w + "'");
    }
    return std::stoll(w);
  }
  std::uint8_t axis() {
    const std::string w = word("an axis");
    if (w == "x" || w == "X") return 0;
    if (w == "y" || w == "Y") return 1;
    if (w == "z" || w == "Z") return 2;
    fail("unknown axis '" + w + "' (x, y or z)");
  }
  Op op() {
    const std::string w = word("a comparison");
    if (w == "==") return Op::Eq;
    if (w == "!=") return Op::Ne;
    if (w == "<") return Op::Lt;
    if (w == "<=") return Op::Le;
    if (w == ">") return Op::Gt;
    if (w == ">=") return Op::Ge;
    fail("unknown comparison '" + w + "' (== != < <= > >=)");
  }
  void end() const {
    if (!done()) fail("unexpected '" + t_[i_].text + "' at the end of the line");
  }
  int number() const { return n_; }

 private:
  std::string file_;
  int n_;
  std::vector<Token> t_;
  std::size_t i_ = 0;
};

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Words split on blanks; "strings" with \" \\ \r \n \t \xHH; `#` outside a string ends the line.
std::vector<Token> tokenize(const std::string& s, const std::string& file, int n) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '#') {
      break;
    } else if (c == '"') {
      Token t{"", true};
      ++i;
      for (;;) {
        if (i >= s.size()) throw ParseError(file, n, "unterminated string");
        const char d = s[i++];
        if (d == '"') break;
        if (d != '\\') {
          t.text += d;
          continue;
        }
        if (i >= s.size()) throw ParseError(file, n, "unterminated string");
        const char e = s[i++];
        switch (e) {
          case '"': t.text += '"'; break;
          case '\\': t.text += '\\'; break;
          case 'r': t.text += '\r'; break;
          case 'n': t.text += '\n'; break;
          case 't': t.text += '\t'; break;
          case 'x': {
            const int hi = i < s.size() ? hex_digit(s[i]) : -1;
            const int lo = i + 1 < s.size() ? hex_digit(s[i + 1]) : -1;
            if (hi < 0 || lo < 0) throw ParseError(file, n, "\\x needs two hex digits");
            t.text += static_cast<char>(hi * 16 + lo);
            i += 2;
            break;
          }
          default: throw ParseError(file, n, std::string("unknown escape \\") + e);
        }
      }
      out.push_back(std::move(t));
    } else {
      Token t;
      while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != '\r' && s[i] != '#' && s[i] != '"') t.text += s[i++];
      out.push_back(std::move(t));
    }
  }
  return out;
}

bool valid_name(const std::string& n) {
  return !n.empty() && std::all_of(n.begin(), n.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
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
  return l.integer("a value");
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
      const std::int64_t k = l.integer("the index of the lost byte");
      if (k < 0 || static_cast<std::size_t>(k) >= a.bytes.size()) {
        l.fail("lose " + std::to_string(k) + ": the string has bytes 0.." + std::to_string(a.bytes.size() - 1));
      }
      a.bytes.erase(static_cast<std::size_t>(k), 1);
    }
  } else if (verb == "joystick") {
    a.kind = ActionKind::Joystick;
    a.axis = l.axis();
    const std::int64_t v = l.integer("an ADC value");
    if (v < 0 || v > 65535) l.fail("ADC value " + std::to_string(v) + " outside 0..65535");
    a.adc = static_cast<std::uint16_t>(v);
  } else if (verb == "endstop") {
    a.kind = ActionKind::Endstop;
    a.axis = l.axis();
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
    e.axis = l.axis();
    e.op = l.op();
    e.value = quantity_value(l, e.quantity);
    if (e.kind == ExpectKind::Between && e.t_us != kEnd && e.t_us <= e.t0_us) l.fail("between T1 and T2 needs T1 < T2");
  } else if (w == "end") {
    // "expect end pulses y == 500": the same as "expect at end ...".
    if (by) l.fail("'by' and 'end' together");
    e.kind = ExpectKind::At;
    e.quantity = quantity(l);
    e.axis = l.axis();
    e.op = l.op();
    e.value = quantity_value(l, e.quantity);
  } else if (w == "report") {
    e.kind = ExpectKind::Report;
    e.axis = l.axis();
    e.op = l.op();
    if (l.peek_is("counter")) {
      l.word("counter");
      e.value_is_counter = true;
    } else {
      e.value = l.integer("a counter value");
    }
  } else if (w == "replies") {
    e.kind = ExpectKind::Replies;
    e.bytes = l.string("the reply");
    e.op = l.op();
    e.value = l.integer("a count");
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
  bool have_name = false, have_duration = false, have_eeprom = false;
  std::istringstream in(text);
  std::string raw;
  int n = 0;
  while (std::getline(in, raw)) {
    ++n;
    Line l(file, n, tokenize(raw, file, n));
    if (l.done()) continue;
    std::string trimmed = raw.substr(raw.find_first_not_of(" \t"));
    if (const auto hash = trimmed.find(" #"); hash != std::string::npos && trimmed.find('"') == std::string::npos) {
      trimmed.resize(hash);
    }
    const std::string kw = l.word("a statement");
    if (kw == "scenario") {
      if (have_name) l.fail("a second 'scenario' line");
      s.name = l.word("the scenario's name");
      if (!valid_name(s.name)) l.fail("scenario name '" + s.name + "': letters, digits, _ and - only");
      have_name = true;
      l.end();
    } else if (kw == "title") {
      s.title = l.string("the title");
      l.end();
    } else if (kw == "duration") {
      if (have_duration) l.fail("a second 'duration' line");
      s.duration_us = l.time();
      if (s.duration_us < 1000 || s.duration_us % 1000 != 0) l.fail("the duration is whole ms, at least 1 ms");
      have_duration = true;
      l.end();
    } else if (kw == "eeprom") {
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
      parse_expect(l, s, trimmed);
    } else {
      l.fail("unknown statement '" + kw + "' (scenario title duration eeprom at expect)");
    }
  }
  if (!have_name) throw ParseError(file, n, "no 'scenario NAME' line");
  if (!have_duration) throw ParseError(file, n, "no 'duration' line");
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

Scenario parse_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scenario " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

}  // namespace ap::sim::unit3
