// The hc08 scenario language (sim/hc08/scenario.hpp, docs/hc08-sim.md): one statement per line,
// `#` starts a comment outside the title's string, every error names file:line.
#include "sim/hc08/scenario.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <sstream>

#include "core/hc08/board/keypad.hpp"

namespace ap::sim::hc08 {

namespace {

using text::Line;

// The hc08 dialect (docs/hc08-sim.md): a string (the title) escapes only \" and \\, a missing
// word is named, a time may reach a day, and the report shows the line without its comment.
const text::Dialect kDialect = {
    .full_escapes = false, .name_at_end = true, .cut_blank_hash = false, .one_title = true, .time = {15, 86'400'000'000LL}};

}  // namespace

namespace {

constexpr std::array<const char*, kQuantities> kNames = {
    "value", "point", "indicator", "mode", "drive", "direction", "error", "adjusted", "running", "steps",
    "position", "angle", "frequency", "period", "dir", "coils", "port", "presses", "unknown",
};

}  // namespace

const char* quantity_name(Quantity q) {
  const auto i = static_cast<std::size_t>(q);
  return i < kNames.size() ? kNames[i] : "?";
}

bool quantity_of(const std::string& name, Quantity& q) {
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (name == kNames[i]) {
      q = static_cast<Quantity>(i);
      return true;
    }
  }
  return false;
}

std::string format_value(Quantity q, std::int64_t v) {
  switch (q) {
    case Quantity::Mode: return v == 0 ? "A" : v == 1 ? "B" : std::to_string(v);
    case Quantity::Direction:
    case Quantity::Dir: return v > 0 ? "r" : v < 0 ? "l" : "0";
    case Quantity::Coils: {
      std::string s;
      for (int b = 3; b >= 0; --b) s += ((v >> b) & 1) != 0 ? '1' : '0';
      return s;
    }
    case Quantity::Port: {
      static const char* const kHex = "0123456789ABCDEF";
      return std::string("0x") + kHex[(v >> 4) & 0xF] + kHex[v & 0xF];
    }
    default: return std::to_string(v);
  }
}

bool parse_time(const std::string& number, const std::string& unit, std::int64_t& us) {
  return text::parse_time(number, unit, us, kDialect.time);
}

bool key_of(const std::string& name, std::uint8_t& code) {
  // The five keys [T Tab. 4.2] on the kit's numbering (core/hc08/board/keypad.hpp).
  static const std::array<std::pair<const char*, unsigned>, 5> kKeys = {
      {{"set", 5}, {"left", 4}, {"right", 6}, {"plus", 8}, {"minus", 2}}};
  for (const auto& [n, sa] : kKeys) {
    if (name == n) {
      code = hc08_board::key_code(sa);
      return true;
    }
  }
  if (name.size() >= 3 && name.size() <= 4 && name.rfind("SA", 0) == 0 &&
      name.find_first_not_of("0123456789", 2) == std::string::npos) {
    const unsigned n = static_cast<unsigned>(std::stoul(name.substr(2)));
    if (n < 1 || n > 12) return false;
    code = hc08_board::key_code(n);
    return true;
  }
  if (name.size() == 4 && name.rfind("0x", 0) == 0 && name.find_first_not_of("0123456789abcdefABCDEF", 2) == std::string::npos) {
    code = static_cast<std::uint8_t>(std::stoul(name.substr(2), nullptr, 16));
    return true;
  }
  return false;
}

namespace {

Quantity quantity(Line& l) {
  const std::string w = l.word("a quantity");
  Quantity q = Quantity::Value;
  if (quantity_of(w, q)) return q;
  std::string all;
  for (const char* n : kNames) all += std::string(all.empty() ? "" : " ") + n;
  l.fail("unknown quantity '" + w + "' (" + all + ")");
}

std::int64_t integer(Line& l, const std::string& w) {
  std::size_t k = (!w.empty() && (w[0] == '-' || w[0] == '+')) ? 1 : 0;
  if (k == w.size() || w.find_first_not_of("0123456789", k) != std::string::npos || w.size() - k > 15) {
    l.fail("expected an integer, got '" + w + "'");
  }
  return std::stoll(w);
}

// The value of an expectation, written as its quantity is (docs/hc08-sim.md "Quantities").
std::int64_t quantity_value(Line& l, Quantity q) {
  const std::string w = l.word("a value");
  switch (q) {
    case Quantity::Mode:
      if (w == "A") return 0;
      if (w == "B") return 1;
      l.fail("mode is A or B, got '" + w + "'");
    case Quantity::Drive:
      if (w == "4" || w == "8") return std::stoll(w);
      l.fail("drive is 4 or 8, got '" + w + "'");
    case Quantity::Direction:
    case Quantity::Dir:
      if (w == "r" || w == "+" || w == "1" || w == "+1") return 1;
      if (w == "l" || w == "-" || w == "-1") return -1;
      if (q == Quantity::Dir && w == "0") return 0;
      l.fail(std::string(quantity_name(q)) + " is r or l, got '" + w + "'");
    case Quantity::Error:
    case Quantity::Adjusted:
    case Quantity::Running:
      if (w == "0" || w == "1") return w == "1" ? 1 : 0;
      l.fail(std::string(quantity_name(q)) + " is 0 or 1, got '" + w + "'");
    case Quantity::Coils:
      if (w.size() == 4 && w.find_first_not_of("01") == std::string::npos) return std::stoll(w, nullptr, 2);
      l.fail("coils are four binary digits in rotational order, e.g. 0011, got '" + w + "'");
    case Quantity::Port:
      if (w.size() >= 3 && w.size() <= 4 && w.rfind("0x", 0) == 0 && w.find_first_not_of("0123456789abcdefABCDEF", 2) == std::string::npos) {
        return std::stoll(w.substr(2), nullptr, 16);
      }
      {
        const std::int64_t v = integer(l, w);
        if (v < 0 || v > 255) l.fail("port is a byte, got '" + w + "'");
        return v;
      }
    default: return integer(l, w);
  }
}

void parse_press(Line& l, Scenario& s, std::int64_t t) {
  Action a;
  a.t_us = t;
  a.line = l.number();
  a.key = l.word("a key");
  if (!key_of(a.key, a.code)) l.fail("unknown key '" + a.key + "' (set left right plus minus, SA1..SA12, or 0xHH)");
  if (a.code == 0) l.fail("0x00 is the scan of no key");
  std::uint32_t times = 1;
  std::int64_t hold = kDefaultHoldUs;
  for (bool seen_x = false, seen_hold = false; !l.done();) {
    const std::string w = l.word("xN, hold T or bounce");
    if (!seen_x && w.size() >= 2 && w.size() <= 4 && w[0] == 'x' && w.find_first_not_of("0123456789", 1) == std::string::npos) {
      times = static_cast<std::uint32_t>(std::stoul(w.substr(1)));
      if (times == 0) l.fail("x0 presses nothing");
      seen_x = true;
    } else if (!seen_hold && w == "hold") {
      hold = l.time();
      if (hold < 1000 || hold % 1000 != 0) l.fail("a hold is whole ms, at least 1 ms (the scan runs once per ms)");
      seen_hold = true;
    } else if (!a.bounce && w == "bounce") {
      a.bounce = true;
    } else {
      l.fail("unexpected '" + w + "' after the key (xN, hold T, bounce)");
    }
  }
  if (a.bounce && hold <= 2 * kBounceMs * 1000) {
    l.fail("a bouncing press needs a hold longer than " + std::to_string(2 * kBounceMs) + " ms (bounce at both ends)");
  }
  a.hold_ms = static_cast<std::uint32_t>(hold / 1000);
  for (std::uint32_t k = 0; k < times; ++k) {
    Action each = a;
    each.t_us = t + static_cast<std::int64_t>(k) * (hold + kRepeatGapUs);
    s.actions.push_back(each);
  }
}

// `end` stands for the duration, known only at the end of the file: kEnd marks it until then.
constexpr std::int64_t kEnd = -1;

void parse_expect(Line& l, Scenario& s, const std::string& text) {
  Expectation e;
  e.line = l.number();
  e.text = text;
  const auto time_or_end = [&]() -> std::int64_t {
    if (l.peek_is("end")) {
      l.word("end");
      return kEnd;
    }
    return l.time();
  };
  const std::string w = l.word("an expectation");
  if (w == "at") {
    e.kind = ExpectKind::At;
    e.t_us = time_or_end();
  } else if (w == "end") {
    e.kind = ExpectKind::At;
    e.t_us = kEnd;
  } else if (w == "by") {
    e.kind = ExpectKind::Throughout;
    e.t0_us = l.time();
    e.t_us = kEnd;
  } else if (w == "between" || w == "change") {
    e.kind = w == "between" ? ExpectKind::Throughout : ExpectKind::Change;
    if (w == "change") l.expect_word("between");
    e.t0_us = l.time();
    l.expect_word("and");
    e.t_us = time_or_end();
    if (e.t_us != kEnd && e.t_us <= e.t0_us) l.fail("between T1 and T2 needs T1 < T2");
  } else {
    l.fail("unknown expectation '" + w + "' (at, end, by, between, change between)");
  }
  e.quantity = quantity(l);
  if (e.kind == ExpectKind::Change && e.quantity != Quantity::Steps && e.quantity != Quantity::Position &&
      e.quantity != Quantity::Presses && e.quantity != Quantity::Unknown) {
    l.fail("change between takes a count: steps, position, presses or unknown");
  }
  e.op = l.op();
  e.value = e.kind == ExpectKind::Change ? integer(l, l.word("a value")) : quantity_value(l, e.quantity);
  l.end();
  s.expectations.push_back(std::move(e));
}

}  // namespace

Scenario parse(const std::string& text, const std::string& file) {
  Scenario s;
  s.file = file;
  text::Header head;
  const int n = text::each_statement(text, file, kDialect, [&](Line& l, const std::string& shown) {
    const std::string kw = l.word("a statement");
    if (head.read(kw, l)) return;
    if (kw == "at") {
      const std::int64_t t = l.time();
      l.expect_word("press");
      parse_press(l, s, t);
    } else if (kw == "expect") {
      parse_expect(l, s, shown);
    } else {
      l.fail("unknown statement '" + kw + "' (scenario title duration at expect)");
    }
  });
  head.check(file, n);
  s.name = head.name;
  s.title = head.title;
  s.duration_us = head.duration_us;
  std::stable_sort(s.actions.begin(), s.actions.end(), [](const Action& a, const Action& b) { return a.t_us < b.t_us; });
  for (std::size_t i = 0; i < s.actions.size(); ++i) {
    const Action& a = s.actions[i];
    if (a.t_us >= s.duration_us) throw ParseError(file, a.line, "press at or after the end of the run");
    // One key at a time: the scan finds the first column with a key down, so two keys held at
    // once would read as one (seed 002 §5.2.3).
    if (i > 0) {
      const Action& p = s.actions[i - 1];
      if (a.t_us < p.t_us + static_cast<std::int64_t>(p.hold_ms) * 1000) {
        throw ParseError(file, a.line, "press while the key of line " + std::to_string(p.line) + " is still held (one key at a time)");
      }
    }
  }
  for (Expectation& e : s.expectations) {
    if (e.t_us == kEnd) e.t_us = s.duration_us;
    if (e.t_us > s.duration_us || e.t0_us > s.duration_us) throw ParseError(file, e.line, "expectation after the end of the run");
    if (e.kind != ExpectKind::At && e.t0_us >= e.t_us) throw ParseError(file, e.line, "the window is empty (T1 must be before T2)");
  }
  return s;
}

Scenario parse_file(const std::string& path) { return parse(text::read_file(path), path); }

}  // namespace ap::sim::hc08
