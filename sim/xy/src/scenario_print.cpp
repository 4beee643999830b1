// The canonical text of an XY scenario (docs/scenarios.md: `to_text()` prints the canonical
// form, and parsing it again gives the same scenario): every header statement, quantities in
// their canonical units, times in seconds. Apart from the parser, it shares with it the tables
// of scenario_words.hpp and the kit's string quoting, so what it writes reads back unchanged.
#include <charconv>
#include <sstream>
#include <string>
#include <variant>

#include "scenario_words.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::sim::xy::scenario {
namespace {

// The shortest fixed notation that reads back as v; a double needs up to ~330 characters so
// (1e308, 5e-324), and a buffer that cannot hold it would print whatever it held.
std::string fmt_double(double v) {
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
  return std::string(buf, r.ptr);
}

std::string q(const Quantity& x) {
  const std::string u(unit_name(x.dim));
  return fmt_double(x.value) + (u.empty() ? "" : " " + u);
}
std::string tm(std::int64_t us) { return fmt_double(static_cast<double>(us) / 1e6) + " s"; }
std::string tg(const Target& t) { return t.all ? std::string() : std::string("@").append(std::to_string(t.board)).append(" "); }
std::string quoted(const std::string& s) { return text::quote(s, kDialect); }

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
    o << ' ' << tg(e.target) << e.subject << ' ' << text::op_text(e.op) << ' ';
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
