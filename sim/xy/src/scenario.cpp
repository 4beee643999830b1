// Scenario parser and printer (docs/scenarios.md).
#include "sim/xy/scenario.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace ap::sim::xy::scenario {
namespace {

struct UnitDef {
  std::string_view name;
  Dim dim;
  double factor;   // to the canonical unit
};

constexpr std::array kUnits{
    UnitDef{"um", Dim::length, 1.0},        UnitDef{"mm", Dim::length, 1e3},
    UnitDef{"cm", Dim::length, 1e4},        UnitDef{"m", Dim::length, 1e6},
    UnitDef{"um/s", Dim::speed, 1.0},       UnitDef{"mm/s", Dim::speed, 1e3},
    UnitDef{"m/s", Dim::speed, 1e6},        UnitDef{"um/s2", Dim::accel, 1.0},
    UnitDef{"um/s^2", Dim::accel, 1.0},     UnitDef{"mm/s2", Dim::accel, 1e3},
    UnitDef{"mm/s^2", Dim::accel, 1e3},     UnitDef{"m/s2", Dim::accel, 1e6},
    UnitDef{"m/s^2", Dim::accel, 1e6},      UnitDef{"us", Dim::time, 1.0},
    UnitDef{"ms", Dim::time, 1e3},          UnitDef{"s", Dim::time, 1e6},
    UnitDef{"min", Dim::time, 60e6},        UnitDef{"mV", Dim::voltage, 1.0},
    UnitDef{"V", Dim::voltage, 1e3},        UnitDef{"mA", Dim::current, 1.0},
    UnitDef{"A", Dim::current, 1e3},        UnitDef{"mdegC", Dim::temperature, 1.0},
    UnitDef{"degC", Dim::temperature, 1e3}, UnitDef{"mdeg", Dim::angle, 1.0},
    UnitDef{"deg", Dim::angle, 1e3},        UnitDef{"%", Dim::ratio, 1.0},
};

const UnitDef* find_unit(std::string_view u) {
  for (const UnitDef& d : kUnits) {
    if (d.name == u) return &d;
  }
  return nullptr;
}

std::string_view dim_name(Dim d) {
  switch (d) {
    case Dim::none: return "a plain number";
    case Dim::length: return "a length (um, mm, ...)";
    case Dim::speed: return "a speed (um/s, mm/s, ...)";
    case Dim::accel: return "an acceleration (um/s2, mm/s2, ...)";
    case Dim::time: return "a time (us, ms, s, min)";
    case Dim::voltage: return "a voltage (mV, V)";
    case Dim::current: return "a current (mA, A)";
    case Dim::temperature: return "a temperature (mdegC, degC)";
    case Dim::angle: return "an angle (mdeg, deg)";
    case Dim::ratio: return "a rate in %";
  }
  return "?";
}

struct Verbs {
  std::string_view name;
  Verb verb;
};
constexpr std::array kVerbs{
    Verbs{"jog", Verb::jog},           Verbs{"stop", Verb::stop},
    Verbs{"goto", Verb::go_to},        Verbs{"move", Verb::move},
    Verbs{"home", Verb::home},         Verbs{"set speed", Verb::set_speed},
    Verbs{"set accel", Verb::set_accel}, Verbs{"save", Verb::save},
    Verbs{"reboot", Verb::reboot},     Verbs{"subscribe", Verb::subscribe},
    Verbs{"unsubscribe", Verb::unsubscribe}, Verbs{"charger", Verb::charger},
    Verbs{"usb", Verb::usb},           Verbs{"battery", Verb::battery},
    Verbs{"temperature", Verb::temperature}, Verbs{"rotate", Verb::rotate},
    Verbs{"ble", Verb::ble},           Verbs{"tmc", Verb::tmc},
    Verbs{"link cut", Verb::link_cut}, Verbs{"link restore", Verb::link_restore},
    Verbs{"peripherals", Verb::peripherals}, Verbs{"endstop", Verb::endstop},
    Verbs{"button", Verb::button},     Verbs{"raw", Verb::raw}, Verbs{"gcode", Verb::gcode},
};

constexpr std::array<std::string_view, 6> kOps{"==", "!=", "<", "<=", ">", ">="};
constexpr std::array<std::string_view, 5> kFaults{"drop", "duplicate", "reorder", "corrupt", "delay"};
constexpr std::array<std::string_view, 3> kDirs{"both", "to_board", "to_pc"};
constexpr std::array<std::string_view, 5> kWhens{"at", "always", "from", "by", "end"};

bool is_word(std::string_view w) {
  return !w.empty() && std::all_of(w.begin(), w.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '+' ||
           c == '-' || c == '.';
  });
}

bool is_name(std::string_view w) {
  return !w.empty() && std::all_of(w.begin(), w.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::string fmt_double(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
  return std::string(buf, r.ptr);
}

class LineParser {
 public:
  LineParser(std::vector<std::string> toks, const std::string& file, int line)
      : t_(std::move(toks)), file_(file), line_(line) {}

  [[noreturn]] void fail(const std::string& what) const { throw ParseError(file_, line_, what); }
  bool done() const { return i_ >= t_.size(); }
  const std::string& peek() const {
    static const std::string empty;
    return done() ? empty : t_[i_];
  }
  std::string next(const char* what) {
    if (done()) fail(std::string("expected ") + what);
    return t_[i_++];
  }
  bool accept(std::string_view w) {
    if (!done() && t_[i_] == w) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect_end() const {
    if (!done()) fail("unexpected '" + t_[i_] + "'");
  }
  std::string word(const char* what) {
    std::string w = next(what);
    if (!is_word(w)) fail(std::string("expected ") + what + ", got '" + w + "'");
    return w;
  }
  std::string one_of(std::initializer_list<std::string_view> options, const char* what) {
    std::string w = next(what);
    if (std::find(options.begin(), options.end(), w) == options.end()) {
      std::string list;
      for (auto o : options) {
        if (!list.empty()) list += '|';
        list.append(o);
      }
      fail(std::string(what) + " must be " + list + ", got '" + w + "'");
    }
    return w;
  }
  char axis() {
    const std::string a = next("an axis (x or y)");
    if (a != "x" && a != "y") fail("axis must be x or y, got '" + a + "'");
    return a[0];
  }
  // A number with an optional unit, attached ("20mm") or separate ("20 mm"), checked against want.
  Quantity quantity(Dim want, const char* what, bool allow_sign = true) {
    const Quantity q = any_quantity(what, allow_sign, want);
    if (q.dim != want) {
      fail(std::string(what) + ": expected " + std::string(dim_name(want)) + ", got " + std::string(dim_name(q.dim)));
    }
    return q;
  }
  Quantity any_quantity(const char* what, bool allow_sign = true, Dim want = Dim::none) {
    const std::string tok = next(what);
    std::size_t k = 0;
    if (k < tok.size() && (tok[k] == '+' || tok[k] == '-')) ++k;
    const std::size_t digits_from = k;
    while (k < tok.size() && ((tok[k] >= '0' && tok[k] <= '9') || tok[k] == '.')) ++k;
    if (k == digits_from) fail(std::string("expected ") + what + ", got '" + tok + "'");
    if (k + 1 < tok.size() && (tok[k] == 'e' || tok[k] == 'E')) {   // exponent: 1e-3, 2E+6
      std::size_t e = k + 1;
      if (tok[e] == '+' || tok[e] == '-') ++e;
      const std::size_t exp_digits = e;
      while (e < tok.size() && tok[e] >= '0' && tok[e] <= '9') ++e;
      if (e > exp_digits) k = e;
    }
    if (!allow_sign && tok[0] == '-') fail(std::string(what) + " must not be negative");
    double v = 0.0;
    const char* first = tok.data() + (tok[0] == '+' ? 1 : 0);
    const auto r = std::from_chars(first, tok.data() + k, v);
    if (r.ec != std::errc() || r.ptr != tok.data() + k) fail("bad number '" + tok.substr(0, k) + "'");
    std::string unit = tok.substr(k);
    if (unit.empty() && !done() && find_unit(peek()) != nullptr) unit = next("unit");
    if (unit.empty()) {
      if (want != Dim::none) fail(std::string(what) + ": '" + tok + "' needs a unit: " + std::string(dim_name(want)));
      return Quantity{v, Dim::none};
    }
    const UnitDef* u = find_unit(unit);
    if (u == nullptr) fail("unknown unit '" + unit + "'");
    return Quantity{v * u->factor, u->dim};
  }
  std::int64_t time(const char* what) {
    const Quantity q = quantity(Dim::time, what, false);
    return static_cast<std::int64_t>(std::llround(q.value));
  }

 private:
  std::vector<std::string> t_;
  const std::string& file_;
  int line_;
  std::size_t i_ = 0;
};

std::vector<std::string> tokenize(std::string_view line, const std::string& file, int n) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '#') {
      break;
    } else if (c == '"') {
      std::string s = "\"";
      ++i;
      while (i < line.size() && line[i] != '"') {
        if (line[i] == '\\' && i + 1 < line.size()) ++i;
        s += line[i++];
      }
      if (i >= line.size()) throw ParseError(file, n, "unterminated string");
      ++i;
      out.push_back(s + "\"");
    } else {
      const std::size_t b = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != '#') ++i;
      out.emplace_back(line.substr(b, i - b));
    }
  }
  return out;
}

std::string unquote(LineParser& p, const std::string& tok, const char* what) {
  if (tok.size() < 2 || tok.front() != '"') p.fail(std::string(what) + " must be a \"quoted string\"");
  return tok.substr(1, tok.size() - 2);
}

Target target(LineParser& p, const Scenario& s) {
  Target t;
  const std::string& w = p.peek();
  if (w.size() > 1 && w[0] == '@') {
    const std::string tok = p.next("@board");
    if (tok == "@all") return t;
    std::uint32_t n = 0;
    const auto r = std::from_chars(tok.data() + 1, tok.data() + tok.size(), n);
    if (r.ec != std::errc() || r.ptr != tok.data() + tok.size()) p.fail("bad board selector '" + tok + "'");
    if (n >= s.boards) p.fail(std::string("board ").append(std::to_string(n)).append(" does not exist (boards ").append(std::to_string(s.boards)).append(")"));
    t.all = false;
    t.board = n;
  }
  return t;
}

Action action(LineParser& p, Action a) {
  std::string v = p.next("an action");
  if (v == "set" || v == "link") {
    v += ' ';
    v += p.next("the rest of the action");
  }
  const auto it = std::find_if(kVerbs.begin(), kVerbs.end(), [&](const Verbs& x) { return x.name == v; });
  if (it == kVerbs.end()) p.fail("unknown action '" + v + "'");
  a.verb = it->verb;
  switch (a.verb) {
    case Verb::jog:
      a.axis = p.axis();
      a.word = p.one_of({"+", "-"}, "jog direction");
      if (!p.done()) a.word2 = p.one_of({"fast", "slow"}, "jog speed");
      break;
    case Verb::stop:
    case Verb::home:
      a.axis = p.axis();
      break;
    case Verb::go_to:
      a.axis = p.axis();
      a.amount = p.quantity(Dim::length, "target position");
      if (!p.done()) a.word2 = p.one_of({"fast", "slow"}, "positioning speed");
      break;
    case Verb::move:
      a.axis = p.axis();
      a.amount = p.quantity(Dim::length, "distance");
      if (!p.done()) a.word2 = p.one_of({"fast", "slow"}, "positioning speed");
      break;
    case Verb::set_speed:
      a.word = p.one_of({"fast", "slow"}, "speed level");
      a.amount = p.quantity(Dim::speed, "speed", false);
      break;
    case Verb::set_accel:
      a.amount = p.quantity(Dim::accel, "acceleration", false);
      break;
    case Verb::save:
    case Verb::reboot:
    case Verb::link_restore:
      break;
    case Verb::subscribe:
    case Verb::unsubscribe:
      a.word = p.one_of({"battery", "charge_current", "temperature", "rotation", "all"}, "subscriber");
      break;
    case Verb::charger:
    case Verb::usb:
      a.word = p.one_of({"plug", "unplug"}, "plug state");
      break;
    case Verb::battery:
      a.amount = p.quantity(Dim::voltage, "battery voltage", false);
      break;
    case Verb::temperature:
      a.amount = p.quantity(Dim::temperature, "temperature");
      break;
    case Verb::rotate:
      a.amount = p.quantity(Dim::angle, "rotation");
      break;
    case Verb::ble:
      a.word = p.one_of({"shutdown", "standby", "connected", "session"}, "BLE state (Tab. 7-2)");
      break;
    case Verb::tmc:
      a.axis = p.axis();
      a.word = p.word("a TMC2130 field name");
      a.amount = p.quantity(Dim::none, "field value", false);
      break;
    case Verb::link_cut:
      if (!p.done()) a.amount = p.quantity(Dim::time, "cut duration", false);
      break;
    case Verb::peripherals:
      a.word = p.one_of({"on", "off"}, "peripherals");
      break;
    case Verb::endstop:
      a.axis = p.axis();
      a.word = p.one_of({"min", "max"}, "endstop");
      a.word2 = p.one_of({"on", "off"}, "endstop state");
      break;
    case Verb::button:
      a.word = p.one_of({"press", "hold"}, "button action");
      break;
    case Verb::raw: {
      const std::string tok = p.next("a \"quoted\" frame");
      a.word = unquote(p, tok, "raw frame");
      break;
    }
    case Verb::gcode: {
      const std::string tok = p.next("a \"quoted\" G-code file");
      a.word = unquote(p, tok, "G-code file");
      a.word2 = p.done() ? "tolerant" : p.one_of({"thesis", "tolerant"}, "G-code dialect");
      break;
    }
  }
  p.expect_end();
  return a;
}

}  // namespace

std::string_view unit_name(Dim d) {
  switch (d) {
    case Dim::none: return "";
    case Dim::length: return "um";
    case Dim::speed: return "um/s";
    case Dim::accel: return "um/s2";
    case Dim::time: return "us";
    case Dim::voltage: return "mV";
    case Dim::current: return "mA";
    case Dim::temperature: return "mdegC";
    case Dim::angle: return "mdeg";
    case Dim::ratio: return "%";
  }
  return "";
}

std::string_view to_string(Verb v) {
  for (const Verbs& x : kVerbs) {
    if (x.verb == v) return x.name;
  }
  return "?";
}

std::optional<Dim> subject_dim(std::string_view s) {
  auto starts = [&](std::string_view p) { return s.substr(0, p.size()) == p; };
  if (s.size() > 2 && (s[0] == 'x' || s[0] == 'y') && s[1] == '.') {
    const std::string_view f = s.substr(2);
    if (f == "pos" || f == "target") return Dim::length;
    if (f == "speed") return Dim::speed;
    if (f == "dir" || f == "status" || f == "endstop_min" || f == "endstop_max" || f == "enabled" ||
        f == "blocked" || f == "lost_steps") {
      return Dim::none;
    }
    return std::nullopt;
  }
  if (starts("board.")) {
    const std::string_view f = s.substr(6);
    if (f == "battery") return Dim::voltage;
    if (f == "charge_current") return Dim::current;
    if (f == "temperature") return Dim::temperature;
    if (f == "rotation") return Dim::angle;
    if (f == "state" || f == "led" || f == "ble" || f == "charger" || f == "usb" || f == "low_battery" ||
        f == "peripherals") {
      return Dim::none;
    }
    return std::nullopt;
  }
  if (starts("param.")) {
    const std::string_view f = s.substr(6);
    if (f == "accel") return Dim::accel;
    if (f == "speed_fast" || f == "speed_slow") return Dim::speed;
    if (f == "lead") return Dim::length;
    if (is_name(f)) return Dim::none;
    return std::nullopt;
  }
  if (s == "echo.count" || s == "echo.x.id" || s == "echo.y.id" || s == "echo.x.data" || s == "echo.y.data" ||
      s == "echo.last") {
    return Dim::none;
  }
  if ((starts("tmc.x.") || starts("tmc.y.")) && is_word(s.substr(6))) return Dim::none;
  if ((starts("fram.") && is_name(s.substr(5))) || (starts("sub.") && is_name(s.substr(4)))) return Dim::none;
  if (s == "gaps" || s == "watchdog_stops" || s == "rejected" || s == "lost_steps" || s == "echoes" ||
      s == "commands" || s == "delivered" || s == "failed" || s == "retransmissions") {
    return Dim::none;
  }
  // The client's outcomes (docs/protocol.md "Outcomes"), counted by kind.
  for (const char* k : {"done", "refused", "blocked", "superseded", "unconfirmed", "link_down", "invalid"}) {
    if (s == std::string("outcome.") + k) return Dim::none;
  }
  return std::nullopt;
}

Scenario parse(std::string_view text, const std::string& file) {
  Scenario s;
  bool have_name = false;
  bool have_duration = false;
  std::int64_t last_at = 0;
  int n = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string_view raw = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++n;
    std::vector<std::string> toks = tokenize(raw, file, n);
    if (toks.empty()) {
      if (eol == text.size()) break;
      continue;
    }
    LineParser p(std::move(toks), file, n);
    const std::string kw = p.next("a keyword");
    if (!have_name && kw != "scenario") p.fail("a scenario file starts with 'scenario NAME'");
    if (kw == "scenario") {
      if (have_name) p.fail("second 'scenario' line");
      s.name = p.next("a scenario name");
      if (!is_name(s.name)) p.fail("scenario name must be [a-z0-9_-]+");
      have_name = true;
    } else if (kw == "title") {
      s.title = unquote(p, p.next("a \"title\""), "title");
    } else if (kw == "boards") {
      const Quantity q = p.quantity(Dim::none, "board count", false);
      if (q.value < 1 || q.value > 64 || q.value != std::floor(q.value)) p.fail("boards must be 1..64");
      if (!s.actions.empty() || !s.expectations.empty()) p.fail("'boards' must come before actions and expectations");
      s.boards = static_cast<std::uint32_t>(q.value);
    } else if (kw == "duration") {
      s.duration_us = p.time("run duration");
      if (s.duration_us <= 0) p.fail("duration must be positive");
      have_duration = true;
    } else if (kw == "period") {
      s.period_us = p.time("command period");
      if (s.period_us <= 0) p.fail("period must be positive");
    } else if (kw == "timing") {
      s.timing = p.one_of({"lockstep", "realtime"}, "timing") == "lockstep" ? Timing::lockstep : Timing::realtime;
    } else if (kw == "seed") {
      const Quantity q = p.quantity(Dim::none, "seed", false);
      s.seed = static_cast<std::uint64_t>(q.value);
    } else if (kw == "first_seq") {
      const Quantity q = p.quantity(Dim::none, "first seq", false);
      if (q.value < 0 || q.value > 999 || q.value != static_cast<double>(static_cast<int>(q.value))) {
        p.fail("first_seq must be an integer 0..999");
      }
      s.first_seq = static_cast<std::uint16_t>(q.value);
    } else if (kw == "baud") {
      const Quantity q = p.quantity(Dim::none, "baud rate", false);
      if (q.value < 300 || q.value > 4e6) p.fail("baud must be 300..4000000");
      s.baud = static_cast<std::uint32_t>(q.value);
    } else if (kw == "board") {
      Setup st;
      st.line = n;
      st.key = p.one_of({"battery", "charger", "usb", "ble", "temperature", "pos", "endstop", "encoder", "param", "fram"},
                        "board setting");
      if (st.key == "battery") {
        st.amount = p.quantity(Dim::voltage, "battery voltage", false);
      } else if (st.key == "charger" || st.key == "usb") {
        st.word = p.one_of({"plugged", "unplugged"}, st.key.c_str());
      } else if (st.key == "ble") {
        st.word = p.one_of({"shutdown", "standby", "connected", "session"}, "BLE state");
      } else if (st.key == "encoder") {
        st.word = p.one_of({"on", "off"}, "encoder fitted");
      } else if (st.key == "temperature") {
        st.amount = p.quantity(Dim::temperature, "temperature");
      } else if (st.key == "pos") {
        st.axis = p.axis();
        st.amount = p.quantity(Dim::length, "carriage position");
      } else if (st.key == "endstop") {
        st.axis = p.axis();
        st.word = p.one_of({"min", "max"}, "endstop");
        st.amount = p.quantity(Dim::length, "endstop position");
      } else {  // param NAME NUMBER[unit] | fram NAME NUMBER
        st.word = p.word("a parameter name");
        st.amount = p.any_quantity("parameter value");
        if (st.key == "fram" && st.amount->dim != Dim::none) p.fail("fram values are raw integers");
      }
      p.expect_end();
      s.setup.push_back(std::move(st));
    } else if (kw == "fault") {
      Fault f;
      f.line = n;
      const std::string k = p.one_of({"drop", "duplicate", "reorder", "corrupt", "delay"}, "fault kind");
      f.kind = static_cast<FaultKind>(std::find(kFaults.begin(), kFaults.end(), k) - kFaults.begin());
      if (f.kind == FaultKind::delay) {
        f.amount = p.quantity(Dim::time, "delay", false);
        if (p.accept("jitter")) f.jitter = p.quantity(Dim::time, "jitter", false);
      } else {
        f.amount = p.quantity(Dim::ratio, "fault rate", false);
        if (f.amount.value > 100) p.fail("fault rate above 100 %");
      }
      while (!p.done()) {
        if (p.accept("from")) {
          f.from_us = p.time("fault start");
          if (p.accept("to")) f.to_us = p.time("fault end");
        } else {
          const std::string d = p.one_of({"both", "to_board", "to_pc"}, "fault direction (or from T [to T])");
          f.dir = static_cast<Direction>(std::find(kDirs.begin(), kDirs.end(), d) - kDirs.begin());
        }
      }
      if (f.to_us && *f.to_us < f.from_us) p.fail("fault ends before it starts");
      s.faults.push_back(f);
    } else if (kw == "at") {
      Action a;
      a.line = n;
      const std::string& t = p.peek();
      const bool rel = !t.empty() && t[0] == '+';
      const std::int64_t at = p.time("action time");
      a.t_us = rel ? last_at + at : at;
      if (a.t_us < last_at) p.fail("actions must be in time order (this one is before the previous 'at')");
      last_at = a.t_us;
      a.target = target(p, s);
      s.actions.push_back(action(p, std::move(a)));
    } else if (kw == "expect") {
      Expectation e;
      e.line = n;
      const std::string w = p.one_of({"at", "always", "from", "by", "end"}, "expectation time (at|always|from|by|end)");
      e.when = static_cast<When>(std::find(kWhens.begin(), kWhens.end(), w) - kWhens.begin());
      if (e.when == When::at || e.when == When::by) {
        e.t_us = p.time("expectation time");
      } else if (e.when == When::between) {
        e.t_us = p.time("window start");
        if (!p.accept("to")) p.fail("expected 'to'");
        e.t2_us = p.time("window end");
        if (e.t2_us < e.t_us) p.fail("window ends before it starts");
      }
      e.target = target(p, s);
      e.subject = p.next("a subject");
      const std::optional<Dim> dim = subject_dim(e.subject);
      if (!dim) p.fail("unknown subject '" + e.subject + "'");
      const std::string op = p.next("a comparison (== != < <= > >=)");
      const auto oi = std::find(kOps.begin(), kOps.end(), op);
      if (oi == kOps.end()) p.fail("unknown comparison '" + op + "'");
      e.op = static_cast<Op>(oi - kOps.begin());
      const std::string& vt = p.peek();
      const bool numeric = !vt.empty() && (std::isdigit(static_cast<unsigned char>(vt[0])) != 0 ||
                                           ((vt[0] == '-' || vt[0] == '+') && vt.size() > 1 &&
                                            std::isdigit(static_cast<unsigned char>(vt[1])) != 0));
      if (numeric) {
        e.value = p.quantity(*dim, "expected value");
      } else {
        if (*dim != Dim::none) p.fail("subject " + e.subject + " needs " + std::string(dim_name(*dim)));
        if (e.op != Op::eq && e.op != Op::ne) p.fail("words compare with == or != only");
        e.value = p.word("an expected value");
      }
      if (p.accept("tol") || p.accept("±") || p.accept("+-")) {
        if (!numeric) p.fail("a tolerance needs a numeric value");
        e.tol = p.quantity(*dim, "tolerance", false);
      }
      p.expect_end();
      s.expectations.push_back(std::move(e));
    } else {
      p.fail("unknown keyword '" + kw + "'");
    }
    if (eol == text.size()) break;
  }
  if (!have_name) throw ParseError(file, n, "empty scenario (no 'scenario NAME' line)");
  if (!have_duration) throw ParseError(file, n, "no 'duration'");
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

bool holds(const Expectation& e, const Value& actual) {
  if (const auto* want = std::get_if<std::string>(&e.value)) {
    const auto* got = std::get_if<std::string>(&actual);
    if (got == nullptr) throw std::invalid_argument("scenario: " + e.subject + " expects a word, got a number");
    // An axis status `blocked` stands for every blocking status the echo names (blk_*).
    const bool is_status = e.subject.size() > 2 && e.subject.substr(1) == ".status";
    const bool same = is_status && *want == "blocked" ? got->rfind("blk_", 0) == 0 : *got == *want;
    if (e.op == Op::eq) return same;
    if (e.op == Op::ne) return !same;
    throw std::invalid_argument("scenario: words compare with == or != only");
  }
  const Quantity& want = std::get<Quantity>(e.value);
  const auto* got = std::get_if<Quantity>(&actual);
  if (got == nullptr) throw std::invalid_argument("scenario: " + e.subject + " expects a number, got a word");
  if (got->dim != want.dim) throw std::invalid_argument("scenario: " + e.subject + ": dimension mismatch");
  // Values reach the runner through unit conversions (µsteps to µm); kSlack keeps a value
  // that is exactly on a bound from failing by a rounding error.
  constexpr double kSlack = 1e-9;
  const double tol = e.tol ? e.tol->value : 0.0;
  const double a = got->value;
  const double v = want.value;
  switch (e.op) {
    case Op::eq: return std::abs(a - v) <= tol + kSlack;
    case Op::ne: return std::abs(a - v) > tol + kSlack;
    case Op::lt: return a < v + tol;
    case Op::le: return a <= v + tol + kSlack;
    case Op::gt: return a > v - tol;
    case Op::ge: return a >= v - tol - kSlack;
  }
  return false;
}

Scenario parse_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ParseError(path, 0, "cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

namespace {

std::string q(const Quantity& x) {
  const std::string u(unit_name(x.dim));
  return fmt_double(x.value) + (u.empty() ? "" : " " + u);
}
std::string tm(std::int64_t us) { return fmt_double(static_cast<double>(us) / 1e6) + " s"; }
std::string tg(const Target& t) { return t.all ? std::string() : std::string("@").append(std::to_string(t.board)).append(" "); }
std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o + "\"";
}

}  // namespace

std::string to_text(const Scenario& s) {
  std::ostringstream o;
  o << "scenario " << s.name << '\n';
  if (!s.title.empty()) o << "title " << quoted(s.title) << '\n';
  o << "boards " << s.boards << "\nduration " << tm(s.duration_us) << "\nperiod " << tm(s.period_us) << "\ntiming "
    << (s.timing == Timing::lockstep ? "lockstep" : "realtime") << "\nseed " << s.seed << "\nfirst_seq " << s.first_seq << "\nbaud " << s.baud << '\n';
  for (const Setup& st : s.setup) {
    o << "board " << st.key;
    if (st.axis != 0) o << ' ' << st.axis;
    if (!st.word.empty()) o << ' ' << st.word;
    if (st.amount) o << ' ' << q(*st.amount);
    o << '\n';
  }
  for (const Fault& f : s.faults) {
    o << "fault " << kFaults[static_cast<std::size_t>(f.kind)] << ' ' << q(f.amount);
    if (f.jitter) o << " jitter " << q(*f.jitter);
    if (f.dir != Direction::both) o << ' ' << kDirs[static_cast<std::size_t>(f.dir)];
    if (f.from_us != 0 || f.to_us) o << " from " << tm(f.from_us);
    if (f.to_us) o << " to " << tm(*f.to_us);
    o << '\n';
  }
  for (const Action& a : s.actions) {
    o << "at " << tm(a.t_us) << ' ' << tg(a.target) << to_string(a.verb);
    if (a.axis != 0) o << ' ' << a.axis;
    if (a.verb == Verb::raw || a.verb == Verb::gcode) {
      o << ' ' << quoted(a.word);
    } else if (!a.word.empty()) {
      o << ' ' << a.word;
    }
    const bool level_last = a.verb == Verb::go_to || a.verb == Verb::move;  // goto x 10 mm slow
    if (!a.word2.empty() && !level_last) o << ' ' << a.word2;
    if (a.amount) {
      o << ' ' << (a.amount->value >= 0 && a.verb == Verb::move ? "+" : "") << q(*a.amount);
    }
    if (!a.word2.empty() && level_last) o << ' ' << a.word2;
    o << '\n';
  }
  for (const Expectation& e : s.expectations) {
    o << "expect ";
    switch (e.when) {
      case When::at: o << "at " << tm(e.t_us); break;
      case When::always: o << "always"; break;
      case When::between: o << "from " << tm(e.t_us) << " to " << tm(e.t2_us); break;
      case When::by: o << "by " << tm(e.t_us); break;
      case When::end: o << "end"; break;
    }
    o << ' ' << tg(e.target) << e.subject << ' ' << kOps[static_cast<std::size_t>(e.op)] << ' ';
    if (const auto* w = std::get_if<std::string>(&e.value)) {
      o << *w;
    } else {
      o << q(std::get<Quantity>(e.value));
    }
    if (e.tol) o << " tol " << q(*e.tol);
    o << '\n';
  }
  return o.str();
}

}  // namespace ap::sim::xy::scenario
