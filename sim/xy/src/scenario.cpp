// The parser of the XY scenario language (docs/scenarios.md): the statements of its "Header",
// "Actions" and "Expectations", read with the shared kit's lines (sim/scenario_text.hpp: the
// words, strings, comments, comparisons and the file:line ParseError every profile's language
// uses). What is XY's own stays here: numbers with units, times as quantities, `at +T`, `@N`,
// the tolerance. Its tables are scenario_words.cpp, its canonical text scenario_print.cpp, the
// judgement of an expectation scenario_holds.cpp.
#include "sim/xy/scenario.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

#include "scenario_words.hpp"

namespace ap::sim::xy::scenario {
namespace {

using text::Line;

// A word of the language's characters (is_word).
std::string word(Line& l, const char* what) {
  std::string w = l.word(what);
  if (!is_word(w)) l.fail(std::string("expected ") + what + ", got '" + w + "'");
  return w;
}

std::string one_of(Line& l, std::initializer_list<std::string_view> options, const char* what) {
  std::string w = l.word(what);
  if (std::find(options.begin(), options.end(), w) == options.end()) {
    std::string list;
    for (auto o : options) {
      if (!list.empty()) list += '|';
      list.append(o);
    }
    l.fail(std::string(what) + " must be " + list + ", got '" + w + "'");
  }
  return w;
}

char axis(Line& l) {
  const std::string a = l.word("an axis (x or y)");
  if (a != "x" && a != "y") l.fail("axis must be x or y, got '" + a + "'");
  return a[0];
}

// A "string"; `missing` names it at the end of the line.
std::string quoted(Line& l, const char* missing, const char* what) {
  const text::Token* t = l.peek();
  if (t != nullptr && !t->quoted) l.fail(std::string(what) + " must be a \"quoted string\"");
  return l.string(missing);
}

// Whether the next token is a word that starts with `c` and goes on (`+2 s`, `@3`).
bool next_starts(const Line& l, char c) {
  const text::Token* t = l.peek();
  return t != nullptr && !t->quoted && t->text.size() > 1 && t->text[0] == c;
}

// A number with an optional unit, attached ("20mm") or separate ("20 mm"); `want` (when not
// none) is named if the unit is missing.
Quantity any_quantity(Line& l, const char* what, bool allow_sign = true, Dim want = Dim::none) {
  const std::string tok = l.word(what);
  std::size_t k = 0;
  if (k < tok.size() && (tok[k] == '+' || tok[k] == '-')) ++k;
  const std::size_t digits_from = k;
  while (k < tok.size() && ((tok[k] >= '0' && tok[k] <= '9') || tok[k] == '.')) ++k;
  if (k == digits_from) l.fail(std::string("expected ") + what + ", got '" + tok + "'");
  if (k + 1 < tok.size() && (tok[k] == 'e' || tok[k] == 'E')) {   // exponent: 1e-3, 2E+6
    std::size_t e = k + 1;
    if (tok[e] == '+' || tok[e] == '-') ++e;
    const std::size_t exp_digits = e;
    while (e < tok.size() && tok[e] >= '0' && tok[e] <= '9') ++e;
    if (e > exp_digits) k = e;
  }
  if (!allow_sign && tok[0] == '-') l.fail(std::string(what) + " must not be negative");
  double v = 0.0;
  const char* first = tok.data() + (tok[0] == '+' ? 1 : 0);
  const auto r = std::from_chars(first, tok.data() + k, v);
  if (r.ec != std::errc() || r.ptr != tok.data() + k) l.fail("bad number '" + tok.substr(0, k) + "'");
  std::string unit = tok.substr(k);
  if (const text::Token* u = l.peek(); unit.empty() && u != nullptr && !u->quoted && find_unit(u->text) != nullptr) {
    unit = l.word("unit");
  }
  if (unit.empty()) {
    if (want != Dim::none) l.fail(std::string(what) + ": '" + tok + "' needs a unit: " + std::string(dim_name(want)));
    return Quantity{v, Dim::none};
  }
  const UnitDef* u = find_unit(unit);
  if (u == nullptr) l.fail("unknown unit '" + unit + "'");
  return Quantity{v * u->factor, u->dim};
}

// A quantity of the dimension `want`.
Quantity quantity(Line& l, Dim want, const char* what, bool allow_sign = true) {
  const Quantity q = any_quantity(l, what, allow_sign, want);
  if (q.dim != want) {
    l.fail(std::string(what) + ": expected " + std::string(dim_name(want)) + ", got " + std::string(dim_name(q.dim)));
  }
  return q;
}

// A time, to the nearest us.
std::int64_t time(Line& l, const char* what) {
  const Quantity q = quantity(l, Dim::time, what, false);
  return static_cast<std::int64_t>(std::llround(q.value));
}

Target target(Line& l, const Scenario& s) {
  Target t;
  if (!next_starts(l, '@')) return t;
  const std::string tok = l.word("@board");
  if (tok == "@all") return t;
  std::uint32_t n = 0;
  const auto r = std::from_chars(tok.data() + 1, tok.data() + tok.size(), n);
  if (r.ec != std::errc() || r.ptr != tok.data() + tok.size()) l.fail("bad board selector '" + tok + "'");
  if (n >= s.boards) l.fail("board " + std::to_string(n) + " does not exist (boards " + std::to_string(s.boards) + ")");
  t.all = false;
  t.board = n;
  return t;
}

Action action(Line& l, Action a) {
  std::string v = l.word("an action");
  if (v == "set" || v == "link") {
    v += ' ';
    v += l.word("the rest of the action");
  }
  const std::optional<Verb> verb = verb_of(v);
  if (!verb) l.fail("unknown action '" + v + "'");
  a.verb = *verb;
  switch (a.verb) {
    case Verb::jog:
      a.axis = axis(l);
      a.word = one_of(l, {"+", "-"}, "jog direction");
      if (!l.done()) a.word2 = one_of(l, {"fast", "slow"}, "jog speed");
      break;
    case Verb::stop:
    case Verb::home:
      a.axis = axis(l);
      break;
    case Verb::go_to:
      a.axis = axis(l);
      a.amount = quantity(l, Dim::length, "target position");
      if (!l.done()) a.word2 = one_of(l, {"fast", "slow"}, "positioning speed");
      break;
    case Verb::move:
      a.axis = axis(l);
      a.amount = quantity(l, Dim::length, "distance");
      if (!l.done()) a.word2 = one_of(l, {"fast", "slow"}, "positioning speed");
      break;
    case Verb::set_speed:
      a.word = one_of(l, {"fast", "slow"}, "speed level");
      a.amount = quantity(l, Dim::speed, "speed", false);
      break;
    case Verb::set_accel:
      a.amount = quantity(l, Dim::accel, "acceleration", false);
      break;
    case Verb::save:
    case Verb::reboot:
    case Verb::link_restore:
      break;
    case Verb::subscribe:
    case Verb::unsubscribe:
      a.word = one_of(l, {"battery", "charge_current", "temperature", "rotation", "all"}, "subscriber");
      break;
    case Verb::charger:
    case Verb::usb:
      a.word = one_of(l, {"plug", "unplug"}, "plug state");
      break;
    case Verb::battery:
      a.amount = quantity(l, Dim::voltage, "battery voltage", false);
      break;
    case Verb::temperature:
      a.amount = quantity(l, Dim::temperature, "temperature");
      break;
    case Verb::rotate:
      a.amount = quantity(l, Dim::angle, "rotation");
      break;
    case Verb::ble:
      a.word = one_of(l, {"shutdown", "standby", "connected", "session"}, "BLE state (Tab. 7-2)");
      break;
    case Verb::tmc:
      a.axis = axis(l);
      a.word = word(l, "a TMC2130 field name");
      a.amount = quantity(l, Dim::none, "field value", false);
      break;
    case Verb::link_cut:
      if (!l.done()) a.amount = quantity(l, Dim::time, "cut duration", false);
      break;
    case Verb::peripherals:
      a.word = one_of(l, {"on", "off"}, "peripherals");
      break;
    case Verb::endstop:
      a.axis = axis(l);
      a.word = one_of(l, {"min", "max"}, "endstop");
      a.word2 = one_of(l, {"on", "off"}, "endstop state");
      break;
    case Verb::button:
      a.word = one_of(l, {"press", "hold"}, "button action");
      break;
    case Verb::raw:
      a.word = quoted(l, "a \"quoted\" frame", "raw frame");
      break;
    case Verb::gcode:
      a.word = quoted(l, "a \"quoted\" G-code file", "G-code file");
      a.word2 = l.done() ? "tolerant" : one_of(l, {"thesis", "tolerant"}, "G-code dialect");
      break;
  }
  l.end();
  return a;
}

Setup setup(Line& l) {
  Setup st;
  st.line = l.number();
  st.key = one_of(l, {"battery", "charger", "usb", "ble", "temperature", "pos", "endstop", "encoder", "param", "fram"},
                  "board setting");
  if (st.key == "battery") {
    st.amount = quantity(l, Dim::voltage, "battery voltage", false);
  } else if (st.key == "charger" || st.key == "usb") {
    st.word = one_of(l, {"plugged", "unplugged"}, st.key.c_str());
  } else if (st.key == "ble") {
    st.word = one_of(l, {"shutdown", "standby", "connected", "session"}, "BLE state");
  } else if (st.key == "encoder") {
    st.word = one_of(l, {"on", "off"}, "encoder fitted");
  } else if (st.key == "temperature") {
    st.amount = quantity(l, Dim::temperature, "temperature");
  } else if (st.key == "pos") {
    st.axis = axis(l);
    st.amount = quantity(l, Dim::length, "carriage position");
  } else if (st.key == "endstop") {
    st.axis = axis(l);
    st.word = one_of(l, {"min", "max"}, "endstop");
    st.amount = quantity(l, Dim::length, "endstop position");
  } else {  // param NAME NUMBER[unit] | fram NAME NUMBER
    st.word = word(l, "a parameter name");
    st.amount = any_quantity(l, "parameter value");
    if (st.key == "fram" && st.amount->dim != Dim::none) l.fail("fram values are raw integers");
  }
  l.end();
  return st;
}

Fault fault(Line& l) {
  Fault f;
  f.line = l.number();
  const std::string k = one_of(l, {"drop", "duplicate", "reorder", "corrupt", "delay"}, "fault kind");
  f.kind = static_cast<FaultKind>(std::find(kFaults.begin(), kFaults.end(), k) - kFaults.begin());
  if (f.kind == FaultKind::delay) {
    f.amount = quantity(l, Dim::time, "delay", false);
    if (l.accept("jitter")) f.jitter = quantity(l, Dim::time, "jitter", false);
  } else {
    f.amount = quantity(l, Dim::ratio, "fault rate", false);
    if (f.amount.value > 100) l.fail("fault rate above 100 %");
  }
  while (!l.done()) {
    if (l.accept("from")) {
      f.from_us = time(l, "fault start");
      if (l.accept("to")) f.to_us = time(l, "fault end");
    } else {
      const std::string d = one_of(l, {"both", "to_board", "to_pc"}, "fault direction (or from T [to T])");
      f.dir = static_cast<Direction>(std::find(kDirs.begin(), kDirs.end(), d) - kDirs.begin());
    }
  }
  if (f.to_us && *f.to_us < f.from_us) l.fail("fault ends before it starts");
  return f;
}

Expectation expectation(Line& l, const Scenario& s) {
  Expectation e;
  e.line = l.number();
  const std::string w = one_of(l, {"at", "always", "from", "by", "end"}, "expectation time (at|always|from|by|end)");
  e.when = static_cast<When>(std::find(kWhens.begin(), kWhens.end(), w) - kWhens.begin());
  if (e.when == When::at || e.when == When::by) {
    e.t_us = time(l, "expectation time");
  } else if (e.when == When::between) {
    e.t_us = time(l, "window start");
    if (!l.accept("to")) l.fail("expected 'to'");
    e.t2_us = time(l, "window end");
    if (e.t2_us < e.t_us) l.fail("window ends before it starts");
  }
  e.target = target(l, s);
  e.subject = l.word("a subject");
  const std::optional<Dim> dim = subject_dim(e.subject);
  if (!dim) l.fail("unknown subject '" + e.subject + "'");
  const std::string op = l.word("a comparison (== != < <= > >=)");
  const std::optional<Op> o = text::op_of(op);
  if (!o) l.fail("unknown comparison '" + op + "'");
  e.op = *o;
  const text::Token* vt = l.peek();
  const bool numeric = vt != nullptr && !vt->quoted &&
                       (std::isdigit(static_cast<unsigned char>(vt->text[0])) != 0 ||
                        ((vt->text[0] == '-' || vt->text[0] == '+') && vt->text.size() > 1 &&
                         std::isdigit(static_cast<unsigned char>(vt->text[1])) != 0));
  if (numeric) {
    e.value = quantity(l, *dim, "expected value");
  } else {
    if (*dim != Dim::none) l.fail("subject " + e.subject + " needs " + std::string(dim_name(*dim)));
    if (e.op != Op::Eq && e.op != Op::Ne) l.fail("words compare with == or != only");
    e.value = word(l, "an expected value");
  }
  if (l.accept("tol") || l.accept("±") || l.accept("+-")) {
    if (!numeric) l.fail("a tolerance needs a numeric value");
    e.tol = quantity(l, *dim, "tolerance", false);
  }
  l.end();
  return e;
}

}  // namespace

Scenario parse(std::string_view src, const std::string& file) {
  Scenario s;
  bool have_name = false;
  bool have_duration = false;
  std::int64_t last_at = 0;
  text::each_statement(std::string(src), file, kDialect, [&](Line& l, const std::string&) {
    const std::string kw = l.word("a keyword");
    if (!have_name && kw != "scenario") l.fail("a scenario file starts with 'scenario NAME'");
    if (kw == "scenario") {
      if (have_name) l.fail("second 'scenario' line");
      s.name = l.word("a scenario name");
      if (!is_name(s.name)) l.fail("scenario name must be [a-z0-9_-]+");
      have_name = true;
    } else if (kw == "title") {
      s.title = quoted(l, "a \"title\"", "title");
    } else if (kw == "boards") {
      const Quantity q = quantity(l, Dim::none, "board count", false);
      if (q.value < 1 || q.value > 64 || q.value != std::floor(q.value)) l.fail("boards must be 1..64");
      if (!s.actions.empty() || !s.expectations.empty()) l.fail("'boards' must come before actions and expectations");
      s.boards = static_cast<std::uint32_t>(q.value);
    } else if (kw == "duration") {
      s.duration_us = time(l, "run duration");
      if (s.duration_us <= 0) l.fail("duration must be positive");
      have_duration = true;
    } else if (kw == "period") {
      s.period_us = time(l, "command period");
      if (s.period_us <= 0) l.fail("period must be positive");
    } else if (kw == "timing") {
      s.timing = one_of(l, {"lockstep", "realtime"}, "timing") == "lockstep" ? Timing::lockstep : Timing::realtime;
    } else if (kw == "seed") {
      const Quantity q = quantity(l, Dim::none, "seed", false);
      s.seed = static_cast<std::uint64_t>(q.value);
    } else if (kw == "first_seq") {
      const Quantity q = quantity(l, Dim::none, "first seq", false);
      if (q.value < 0 || q.value > 999 || q.value != static_cast<double>(static_cast<int>(q.value))) {
        l.fail("first_seq must be an integer 0..999");
      }
      s.first_seq = static_cast<std::uint16_t>(q.value);
    } else if (kw == "baud") {
      const Quantity q = quantity(l, Dim::none, "baud rate", false);
      if (q.value < 300 || q.value > 4e6) l.fail("baud must be 300..4000000");
      s.baud = static_cast<std::uint32_t>(q.value);
    } else if (kw == "board") {
      s.setup.push_back(setup(l));
    } else if (kw == "fault") {
      s.faults.push_back(fault(l));
    } else if (kw == "at") {
      Action a;
      a.line = l.number();
      const bool rel = next_starts(l, '+');
      const std::int64_t at = time(l, "action time");
      a.t_us = rel ? last_at + at : at;
      if (a.t_us < last_at) l.fail("actions must be in time order (this one is before the previous 'at')");
      last_at = a.t_us;
      a.target = target(l, s);
      s.actions.push_back(action(l, std::move(a)));
    } else if (kw == "expect") {
      s.expectations.push_back(expectation(l, s));
    } else {
      l.fail("unknown keyword '" + kw + "'");
    }
  });
  // A whole-file error names the line after the last line break (line 1 of an empty text).
  const int eof_line = static_cast<int>(std::count(src.begin(), src.end(), '\n')) + 1;
  if (!have_name) throw ParseError(file, eof_line, "empty scenario (no 'scenario NAME' line)");
  if (!have_duration) throw ParseError(file, eof_line, "no 'duration'");
  for (const Action& a : s.actions) {
    if (a.t_us > s.duration_us) throw ParseError(file, a.line, "action after the end of the run");
  }
  for (const Expectation& e : s.expectations) {
    if (std::max(e.t_us, e.t2_us) > s.duration_us) throw ParseError(file, e.line, "expectation after the end of the run");
  }
  for (const Fault& f : s.faults) {
    if (f.from_us > s.duration_us) throw ParseError(file, f.line, "fault starts after the end of the run");
  }
  return s;
}

Scenario parse_file(const std::string& path) {
  std::string src;
  try {
    src = text::read_file(path);
  } catch (const std::runtime_error&) {
    throw ParseError(path, 0, "cannot open");
  }
  return parse(src, path);
}

}  // namespace ap::sim::xy::scenario
