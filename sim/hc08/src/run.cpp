// The hc08 run's tester side, the run itself and its report (sim/hc08/hc08.hpp, docs/hc08-sim.md).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "pc/dds/domain.hpp"
#include "sim/hc08/hc08.hpp"
#include "sim/lockstep.hpp"
#include "sim/text.hpp"

namespace ap::sim::hc08 {

namespace {

using Fields = std::map<std::string, std::int64_t>;

std::optional<std::int64_t> integer_of(const std::string& text) {
  const std::size_t k = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() <= k || text.size() > 18 || text.find_first_not_of("0123456789", k) != std::string::npos) return std::nullopt;
  return std::stoll(text);
}

class Tester {
 public:
  Tester(const Scenario& s, const RunOptions& opt, std::uint32_t domain) : s_(s), opt_(opt), link_("hc08", domain) {}

  RunResult run() {
    link_.wait_board();
    const auto wall0 = std::chrono::steady_clock::now();
    for (const std::int64_t t : timeline()) {
      link_.step({}, t);
      for (const Action& a : s_.actions) {
        if (a.t_us == t) act(a);
      }
      read(t);
    }
    // The board's own verdict: its safety checks and its key queue.
    const Fields sum = env_fields(env("summary", s_.duration_us));
    const auto field = [&](const char* k) { return sum.count(k) != 0 ? sum.at(k) : -1; };
    r_.events = static_cast<std::uint64_t>(std::max<std::int64_t>(field("events"), 0));
    r_.steps = static_cast<std::uint64_t>(std::max<std::int64_t>(field("steps"), 0));
    r_.presses = static_cast<std::uint64_t>(std::max<std::int64_t>(field("presses"), 0));
    r_.dropped = static_cast<std::uint64_t>(std::max<std::int64_t>(field("dropped"), 0));
    link_.safety_failures(field("violations"), s_.duration_us, r_.failures);
    if (r_.dropped > 0) r_.failures.push_back("the unit's queue dropped " + std::to_string(r_.dropped) + " keys");
    if (field("t_us") != s_.duration_us) {
      r_.failures.push_back("the board ran to " + std::to_string(field("t_us")) + " us, not " + std::to_string(s_.duration_us));
    }
    judge();
    return link_.finish(std::move(r_), s_.duration_us, wall0);
  }

 private:
  // Every lockstep period, and every time an action or an expectation names.
  std::vector<std::int64_t> timeline() const {
    std::set<std::int64_t> t = lockstep_times(opt_.step_us, s_.duration_us);
    for (const Action& a : s_.actions) t.insert(a.t_us);
    for (const Expectation& e : s_.expectations) {
      t.insert(e.t_us);
      if (e.kind != ExpectKind::At) t.insert(e.t0_us);
    }
    t.erase(0);  // the board starts at 0: a command at 0 runs no event, but an action at 0 still needs one
    std::vector<std::int64_t> out{0};
    out.insert(out.end(), t.begin(), t.end());
    return out;
  }

  std::string env(const std::string& text, std::int64_t t) { return link_.env(text, t); }

  void act(const Action& a) {
    const std::string cmd = "press " + std::to_string(a.code) + " " + std::to_string(a.hold_ms) + (a.bounce ? " 1" : " 0");
    const std::string reply = env(cmd, a.t_us);
    if (reply != "ok") r_.failures.push_back(s_.file + ":" + std::to_string(a.line) + ": the board refused '" + cmd + "': " + reply);
  }

  // What the expectations need at t: values at t, and the windows that end at t.
  void read(std::int64_t t) {
    for (std::size_t i = 0; i < s_.expectations.size(); ++i) {
      const Expectation& e = s_.expectations[i];
      const char* q = quantity_name(e.quantity);
      const bool value_at_t = (e.kind == ExpectKind::At && e.t_us == t) ||
                              (e.kind == ExpectKind::Change && (e.t_us == t || e.t0_us == t));
      if (value_at_t && values_.count({t, e.quantity}) == 0) {
        if (const auto v = integer_of(env(std::string("get ") + q, t))) values_[{t, e.quantity}] = *v;
      }
      if (e.kind == ExpectKind::Throughout && e.t_us == t) {
        ranges_[i] = env_fields(env(std::string("range ") + q + " " + std::to_string(e.t0_us) + " " + std::to_string(e.value), t));
      }
    }
  }

  std::optional<std::int64_t> value_at(std::int64_t t, Quantity q) const {
    const auto it = values_.find({t, q});
    if (it == values_.end()) return std::nullopt;
    return it->second;
  }

  void judge() {
    for (std::size_t i = 0; i < s_.expectations.size(); ++i) {
      const Expectation& e = s_.expectations[i];
      std::string got = "not read";
      bool ok = false;
      switch (e.kind) {
        case ExpectKind::At: {
          if (const auto v = value_at(e.t_us, e.quantity)) {
            ok = compare(*v, e.op, e.value);
            got = std::string(quantity_name(e.quantity)) + " " + format_value(e.quantity, *v);
          }
          break;
        }
        case ExpectKind::Change: {
          const auto v0 = value_at(e.t0_us, e.quantity), v1 = value_at(e.t_us, e.quantity);
          if (v0 && v1) {
            ok = compare(*v1 - *v0, e.op, e.value);
            got = std::to_string(*v0) + " -> " + std::to_string(*v1) + " (change " + std::to_string(*v1 - *v0) + ")";
          }
          break;
        }
        case ExpectKind::Throughout: {
          const auto it = ranges_.find(i);
          if (it == ranges_.end() || it->second.count("samples") == 0 || it->second.at("samples") == 0) break;
          const Fields& f = it->second;
          const std::int64_t lo = f.at("min"), hi = f.at("max"), n = f.at("samples"), eq = f.at("equal");
          switch (e.op) {
            case Op::Eq: ok = eq == n; break;
            case Op::Ne: ok = eq == 0; break;
            case Op::Lt: ok = hi < e.value; break;
            case Op::Le: ok = hi <= e.value; break;
            case Op::Gt: ok = lo > e.value; break;
            case Op::Ge: ok = lo >= e.value; break;
          }
          got = std::to_string(n) + " values from " + format_value(e.quantity, lo) + " to " + format_value(e.quantity, hi);
          break;
        }
      }
      const std::string what = "line " + std::to_string(e.line) + ": " + e.text + " (" + got + ")";
      (ok ? r_.passed : r_.failures).push_back(what);
    }
  }

  const Scenario& s_;
  const RunOptions& opt_;
  LockstepLink link_;
  RunResult r_;
  std::map<std::pair<std::int64_t, Quantity>, std::int64_t> values_;
  std::map<std::size_t, Fields> ranges_;
};

}  // namespace

RunResult run_scenario(const Scenario& s, const RunOptions& opt) {
  return run_lockstep(
      "hc08", s.name, opt,
      [&](const dds::ParticipantPtr& pp, const std::string& out_dir, const std::atomic<bool>* stop) {
        BoardOptions bo;
        bo.out_dir = out_dir;
        return serve_board(pp, bo, std::chrono::seconds(60), stop);
      },
      [&](std::uint32_t domain) { return Tester(s, opt, domain).run(); },
      [&](const RunResult& r) { return format_report(s, r); });
}

std::string format_report(const Scenario& s, const RunResult& r) {
  std::ostringstream o;
  o << "hc08 scenario " << s.name << ": " << (r.pass ? "PASS" : "FAIL") << '\n';
  if (!s.title.empty()) o << "  " << s.title << '\n';
  o << "  virtual " << tstr(r.vtime_us) << ", wall " << r.wall_s << " s, " << r.bus_round_trips << " bus round trips, DDS domain "
    << r.domain << '\n';
  o << "  board: " << r.events << " events checked (safety: maxfreq, start, ramp, reverse, stop, coils), " << r.steps
    << " steps, " << r.presses << " debounced key presses\n";
  for (const std::string& p : r.passed) o << "  ok    " << p << '\n';
  for (const std::string& f : r.failures) o << "  FAIL  " << f << '\n';
  return o.str();
}

}  // namespace ap::sim::hc08
