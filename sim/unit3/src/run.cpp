// The unit3 run's PC side, the run itself and its report (sim/unit3/unit3.hpp, docs/unit3-sim.md).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "pc/dds/domain.hpp"
#include "protocol/unit3/wire/dialect.hpp"
#include "sim/lockstep.hpp"
#include "sim/text.hpp"
#include "sim/unit3/unit3.hpp"

namespace ap::sim::unit3 {

namespace {

namespace w = ap::unit3_wire;

const char* const kAxisName[kAxes] = {"X", "Y", "Z"};

std::span<const std::uint8_t> as_bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// A reply line the PC read, classified with the unit's own dialect (protocol/unit3/wire).
struct Line {
  enum class Kind : std::uint8_t { Report, Error, StepMode, Thread, Malformed } kind = Kind::Malformed;
  std::int64_t t_us = 0;
  std::string bytes;
  std::uint8_t axis = 0;
  std::int64_t count = 0;
};

Line classify(std::int64_t t, const std::string& bytes) {
  Line l;
  l.t_us = t;
  l.bytes = bytes;
  if (const auto r = w::parse_report(as_bytes(bytes))) {
    l.kind = Line::Kind::Report;
    l.axis = static_cast<std::uint8_t>(r->axis);
    l.count = r->count;
  } else if (const auto e = w::parse_error(as_bytes(bytes))) {
    l.kind = Line::Kind::Error;
    l.count = *e;
  } else {
    w::Command c;
    if (w::parse(as_bytes(bytes), c).ok() && (c.kind == w::Kind::StepMode || c.kind == w::Kind::Thread)) {
      l.kind = c.kind == w::Kind::StepMode ? Line::Kind::StepMode : Line::Kind::Thread;
    }
  }
  return l;
}

// A board's state and summary: "pulses=500 counter=16000 ..." (Board::env "state"; the words,
// source=pc, are dropped).
using State = std::map<std::string, std::int64_t>;

class Pc {
 public:
  Pc(const Scenario& s, const RunOptions& opt, std::uint32_t domain) : s_(s), opt_(opt), link_("unit3", domain) {}

  RunResult run() {
    link_.wait_board();
    const auto wall0 = std::chrono::steady_clock::now();
    for (const std::int64_t t : timeline()) {
      std::string bytes;
      for (const Action& a : s_.actions) {
        if (a.t_us == t && a.kind == ActionKind::Send) bytes += a.bytes;
      }
      step(bytes, t);
      for (const Action& a : s_.actions) {
        if (a.t_us == t && a.kind != ActionKind::Send) act(a);
      }
      snapshot(t);
    }
    // The board's own verdict: its safety checks and its reply queue.
    const State sum = env_fields(env("summary", s_.duration_us));
    r_.ticks = static_cast<std::uint64_t>(sum.count("ticks") != 0 ? sum.at("ticks") : 0);
    link_.safety_failures(sum.count("violations") != 0 ? sum.at("violations") : -1, s_.duration_us, r_.failures);
    if (sum.count("dropped") != 0 && sum.at("dropped") > 0) {
      r_.failures.push_back("the unit dropped " + std::to_string(sum.at("dropped")) + " replies (its reply queue was full)");
    }
    if (r_.ticks != static_cast<std::uint64_t>(s_.duration_us / 1000)) {
      r_.failures.push_back("the board ran " + std::to_string(r_.ticks) + " ticks, not " + std::to_string(s_.duration_us / 1000));
    }
    for (std::size_t a = 0; a < kAxes; ++a) {
      const State st = env_fields(env(std::string("state ") + "xyz"[a], s_.duration_us));
      r_.pulses[a] = static_cast<std::uint64_t>(st.count("pulses") != 0 ? st.at("pulses") : 0);
    }
    if (!pending_.empty()) r_.failures.push_back("the PC holds " + std::to_string(pending_.size()) + " bytes without a ';' at the end");
    judge();
    return link_.finish(std::move(r_), s_.duration_us, wall0);
  }

 private:
  std::vector<std::int64_t> timeline() const {
    std::set<std::int64_t> t = lockstep_times(opt_.step_us, s_.duration_us);
    for (const Action& a : s_.actions) t.insert(a.t_us);
    for (const Expectation& e : s_.expectations) {
      t.insert(e.t_us);
      if (e.kind == ExpectKind::Between) t.insert(e.t0_us);
    }
    return {t.begin(), t.end()};
  }

  void step(const std::string& bytes, std::int64_t t) {
    std::size_t off = 0;
    do {
      const std::size_t n = std::min(bytes.size() - off, dds::kFrameMax);
      const std::vector<std::uint8_t> chunk(bytes.begin() + static_cast<std::ptrdiff_t>(off),
                                            bytes.begin() + static_cast<std::ptrdiff_t>(off + n));
      const dds::EchoSample e = link_.step(chunk, t);
      read(e.bytes, t);
      off += n;
    } while (off < bytes.size());
  }

  // The unit's bytes, cut at each ';' into reply lines.
  void read(const std::vector<std::uint8_t>& bytes, std::int64_t t) {
    for (const std::uint8_t b : bytes) {
      pending_ += static_cast<char>(b);
      if (b != static_cast<std::uint8_t>(w::kEnd) && pending_.size() <= w::kReportLength) continue;
      Line l = classify(t, pending_);
      if (l.kind == Line::Kind::Malformed) {
        r_.failures.push_back("the PC read a malformed reply '" + pending_ + "' at " + tstr(t));
      }
      r_.replies.push_back({t, pending_});
      lines_.push_back(std::move(l));
      pending_.clear();
    }
  }

  std::string env(const std::string& text, std::int64_t t) { return link_.env(text, t); }

  void act(const Action& a) {
    std::string cmd;
    switch (a.kind) {
      case ActionKind::Send: return;
      case ActionKind::Joystick: cmd = std::string("joystick ") + "xyz"[a.axis] + " " + std::to_string(a.adc); break;
      case ActionKind::Endstop:
        cmd = std::string("endstop ") + "xyz"[a.axis] + (a.max_end ? " max" : " min") + (a.on ? " on" : " off");
        break;
      case ActionKind::Press: cmd = "press " + a.button; break;
      case ActionKind::PowerCycle: cmd = "power-cycle"; break;
    }
    for (std::uint32_t i = 0; i < (a.kind == ActionKind::Press ? a.times : 1U); ++i) {
      const std::string reply = env(cmd, a.t_us);
      if (reply != "ok") {
        r_.failures.push_back(s_.file + ":" + std::to_string(a.line) + ": the board refused '" + cmd + "': " + reply);
      }
    }
  }

  // The board's state at t for every expectation that reads it there.
  void snapshot(std::int64_t t) {
    for (const Expectation& e : s_.expectations) {
      const bool needs = e.kind == ExpectKind::At || e.kind == ExpectKind::Between ||
                         (e.kind == ExpectKind::Report && e.value_is_counter);
      if (!needs) continue;
      for (const std::int64_t when : {e.t_us, e.kind == ExpectKind::Between ? e.t0_us : e.t_us}) {
        if (when != t || states_.count({t, e.axis}) != 0) continue;
        states_[{t, e.axis}] = env_fields(env(std::string("state ") + "xyz"[e.axis], t));
      }
    }
  }

  std::optional<std::int64_t> quantity_at(std::int64_t t, std::uint8_t axis, Quantity q) const {
    const auto it = states_.find({t, axis});
    if (it == states_.end()) return std::nullopt;
    const auto v = it->second.find(quantity_name(q));
    if (v == it->second.end()) return std::nullopt;
    return v->second;
  }

  void judge() {
    for (const Expectation& e : s_.expectations) {
      std::string got;
      bool ok = false;
      switch (e.kind) {
        case ExpectKind::Report: {
          const Line* last = nullptr;
          for (const Line& l : lines_) {
            if (l.t_us <= e.t_us && l.kind == Line::Kind::Report && l.axis == e.axis) last = &l;
          }
          std::optional<std::int64_t> want = e.value;
          if (e.value_is_counter) want = quantity_at(e.t_us, e.axis, Quantity::Counter);
          if (last == nullptr) {
            got = std::string("no report of ") + kAxisName[e.axis] + " by " + tstr(e.t_us);
          } else if (!want) {
            got = "the board's counter was not read";
          } else {
            ok = compare(last->count, e.op, *want);
            got = "last report " + last->bytes + " at " + tstr(last->t_us) +
                  (e.value_is_counter ? ", counter " + std::to_string(*want) : "");
          }
          break;
        }
        case ExpectKind::Replies: {
          std::int64_t n = 0;
          for (const Line& l : lines_) n += (l.t_us <= e.t_us && l.bytes == e.bytes) ? 1 : 0;
          ok = compare(n, e.op, e.value);
          got = std::to_string(n) + " such replies by " + tstr(e.t_us);
          break;
        }
        case ExpectKind::Settings: {
          std::string m = "none", t = "none";
          for (const Line& l : lines_) {
            if (l.t_us > e.t_us) continue;
            if (l.kind == Line::Kind::StepMode) m = l.bytes;
            if (l.kind == Line::Kind::Thread) t = l.bytes;
          }
          ok = m + t == e.bytes;
          got = "last settings " + m + " " + t;
          break;
        }
        case ExpectKind::NoErrors: {
          std::string errs;
          for (const Line& l : lines_) {
            if (l.t_us <= e.t_us && l.kind == Line::Kind::Error) errs += (errs.empty() ? "" : " ") + l.bytes;
          }
          ok = errs.empty();
          got = errs.empty() ? "none" : errs;
          break;
        }
        case ExpectKind::At: {
          const auto v = quantity_at(e.t_us, e.axis, e.quantity);
          ok = v && compare(*v, e.op, e.value);
          got = v ? std::string(quantity_name(e.quantity)) + " " + std::to_string(*v) : "not read";
          break;
        }
        case ExpectKind::Between: {
          const auto v0 = quantity_at(e.t0_us, e.axis, e.quantity);
          const auto v1 = quantity_at(e.t_us, e.axis, e.quantity);
          ok = v0 && v1 && compare(*v1 - *v0, e.op, e.value);
          got = v0 && v1 ? std::to_string(*v0) + " -> " + std::to_string(*v1) + " (change " + std::to_string(*v1 - *v0) + ")"
                         : "not read";
          break;
        }
      }
      const std::string what = "line " + std::to_string(e.line) + ": " + e.text + " (" + got + ")";
      if (ok) {
        r_.passed.push_back(what);
      } else {
        r_.failures.push_back(what);
      }
    }
  }

  const Scenario& s_;
  const RunOptions& opt_;
  LockstepLink link_;
  RunResult r_;
  std::string pending_;
  std::vector<Line> lines_;
  std::map<std::pair<std::int64_t, std::uint8_t>, State> states_;
};

}  // namespace

RunResult run_scenario(const Scenario& s, const RunOptions& opt) {
  return run_lockstep(
      "unit3", s.name, opt,
      [&](const dds::ParticipantPtr& pp, const std::string& out_dir, const std::atomic<bool>* stop) {
        BoardOptions bo;
        bo.eeprom = s.eeprom;
        bo.out_dir = out_dir;
        return serve_board(pp, bo, std::chrono::seconds(60), stop);
      },
      [&](std::uint32_t domain) { return Pc(s, opt, domain).run(); }, [&](const RunResult& r) { return format_report(s, r); });
}

std::string format_report(const Scenario& s, const RunResult& r) {
  std::ostringstream o;
  o << "unit3 scenario " << s.name << ": " << (r.pass ? "PASS" : "FAIL") << '\n';
  if (!s.title.empty()) o << "  " << s.title << '\n';
  o << "  virtual " << tstr(r.vtime_us) << ", wall " << r.wall_s << " s, " << r.bus_round_trips << " bus round trips, DDS domain "
    << r.domain << '\n';
  o << "  board: " << r.ticks << " ticks checked (safety: reverse, ramp, stop, endstop, gap), STEP pulses X " << r.pulses[0]
    << " Y " << r.pulses[1] << " Z " << r.pulses[2] << '\n';
  std::array<std::size_t, kAxes> reports{};
  std::string others;
  for (const Reply& rep : r.replies) {
    const auto rp = w::parse_report(as_bytes(rep.bytes));
    if (rp) {
      ++reports[static_cast<std::size_t>(rp->axis)];
    } else {
      others += "    " + tstr(rep.t_us) + "  " + rep.bytes + "\n";
    }
  }
  o << "  replies: " << r.replies.size() << " (counter reports X " << reports[0] << " Y " << reports[1] << " Z " << reports[2]
    << ")\n"
    << others;
  for (const std::string& p : r.passed) o << "  ok    " << p << '\n';
  for (const std::string& f : r.failures) o << "  FAIL  " << f << '\n';
  return o.str();
}

}  // namespace ap::sim::unit3
