// The unit3 panel's PC side (session.hpp, docs/panel.md "The unit3 panel").
#include "pc/unit3/panel/session.hpp"

#include <chrono>
#include <optional>
#include <span>

#include "core/unit3/axis/counting.hpp"
#include "core/unit3/board/unit.hpp"
#include "pc/dds/bus.hpp"
#include "protocol/unit3/wire/dialect.hpp"

namespace ap::unit3_panel {

using json = nlohmann::json;

namespace {

std::string line_of(const unit3_wire::Command& c) {
  std::array<std::uint8_t, unit3_wire::kMaxLine> buf{};
  const std::size_t n = unit3_wire::format(c, buf);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
}

const char* axis_name(std::size_t a) { return a == 0 ? "X" : (a == 1 ? "Y" : "Z"); }

// The meaning of an `E…;` code: the wire's line errors (1..7) and the unit's refusals (20..).
std::string error_meaning(std::uint8_t code) {
  if (code >= unit3_wire::kFirstUnitCode) {
    const char* k = unit3_board::refusal_key(code);
    return k != nullptr ? k : "unknown";
  }
  if (code >= 1 && code <= 7) return unit3_wire::error_key(static_cast<unit3_wire::Error>(code));
  return "unknown";
}

}  // namespace

struct Session::Impl {
  std::unique_ptr<dds::PcEndpoint> ep;
  bool on_bus = false;
  std::string rx_rest;                 // a reply line not yet complete
  std::array<std::int64_t, 3> count{}; // the unit's counters as its reports say
  std::array<int, 3> mode{-1, -1, -1}; // as the unit's settings replies say
  std::array<int, 3> thread{-1, -1, -1};
  std::array<int, 3> shown_thread{0, 0, 0};  // the thread the positions are shown in
  std::deque<std::string> replies;
};

Session::Session(Options o) : opt_(o), impl_(std::make_unique<Impl>()) {
  impl_->ep = std::make_unique<dds::PcEndpoint>(opt_.domain, opt_.board);
  loop_ = std::make_unique<web::PacedLoop>(
      opt_.period_us, [this](std::int64_t t) { step(t); },
      [this](const std::string& what) { event({{"type", "error"}, {"what", what}}); });
}

Session::~Session() { stop(); }

void Session::stop() {
  if (loop_) loop_->stop();
}

json Session::tables() {
  json t;
  t["modes"] = json::array();
  for (int m = 0; m <= unit3_wire::kMaxModeDigit; ++m) t["modes"].push_back({{"digit", m}, {"name", m == 0 ? std::string("full") : "1/" + std::to_string(1 << m)}});
  t["threads"] = json::array();
  for (std::size_t k = 0; k < unit3_axis::kThreads; ++k) {
    t["threads"].push_back({{"digit", k}, {"name", unit3_axis::kThreadTable[k].name}, {"pitch_um", unit3_axis::kThreadTable[k].pitch_um}});
  }
  t["max_um"] = kMaxDisplacementUm;
  return t;
}

Sent Session::send(const SendRequest& r) {
  Sent s;
  bool any = false;
  for (std::size_t a = 0; a < 3; ++a) {
    s.conversions[a] = to_counts(r.um[a], r.mode[a], r.thread[a]);
    if (!s.conversions[a].ok) {
      s.error = std::string(axis_name(a)) + ": " + s.conversions[a].error;
      return s;
    }
    any = any || s.conversions[a].count > 0;
  }
  std::vector<std::string> lines;
  std::lock_guard<std::mutex> l(mu_);
  // seed-001.md §7: the settings first when they changed, then the directions and the moves;
  // an axis whose move rounds to 0 counts gets no line (docs/panel.md "The unit3 panel").
  if (std::array<int, 3>{r.mode[0], r.mode[1], r.mode[2]} != sent_mode_) {
    unit3_wire::Command c;
    c.kind = unit3_wire::Kind::StepMode;
    c.digit = r.mode;
    lines.push_back(line_of(c));
  }
  if (std::array<int, 3>{r.thread[0], r.thread[1], r.thread[2]} != sent_thread_) {
    unit3_wire::Command c;
    c.kind = unit3_wire::Kind::Thread;
    c.digit = r.thread;
    lines.push_back(line_of(c));
  }
  if (any) {
    unit3_wire::Command d;
    d.kind = unit3_wire::Kind::Direction;
    for (std::size_t a = 0; a < 3; ++a) d.sign[a] = s.conversions[a].sign;
    lines.push_back(line_of(d));
    for (std::size_t a = 0; a < 3; ++a) {
      if (s.conversions[a].count == 0) continue;
      unit3_wire::Command m;
      m.kind = unit3_wire::Kind::Move;
      m.axis = static_cast<unit3_wire::Axis>(a);
      m.count = s.conversions[a].count;
      lines.push_back(line_of(m));
    }
  }
  for (std::size_t a = 0; a < 3; ++a) {
    sent_mode_[a] = r.mode[a];
    sent_thread_[a] = r.thread[a];
    impl_->shown_thread[a] = r.thread[a];
  }
  queue_locked(lines, false);
  s.ok = true;
  s.lines = std::move(lines);
  return s;
}

void Session::queue_locked(const std::vector<std::string>& lines, bool clear) {
  auto p = std::make_unique<Pending>();
  p->lines = lines;
  p->clear = clear;
  pending_.push_back(std::move(p));
}

Sent Session::send_one(unit3_wire::Kind kind) {
  unit3_wire::Command c;
  c.kind = kind;
  Sent s;
  s.ok = true;
  s.lines = {line_of(c)};
  std::lock_guard<std::mutex> l(mu_);
  queue_locked(s.lines, kind == unit3_wire::Kind::Clear);
  return s;
}

Sent Session::clear() { return send_one(unit3_wire::Kind::Clear); }

Sent Session::get_settings() { return send_one(unit3_wire::Kind::Get); }

json Session::snapshot(std::uint64_t after) const { return pub_.snapshot(after); }

void Session::read(const std::string& line) {
  Impl& m = *impl_;
  m.replies.push_back(line);
  while (m.replies.size() > 30) m.replies.pop_front();
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(line.data()), line.size());
  if (const auto r = unit3_wire::parse_report(bytes)) {
    m.count[static_cast<std::size_t>(r->axis)] = r->count;
    return;
  }
  if (const auto code = unit3_wire::parse_error(bytes)) {
    event({{"type", "refusal"}, {"code", *code}, {"meaning", error_meaning(*code)}, {"line", line}});
    return;
  }
  unit3_wire::Command c;
  if (unit3_wire::parse(bytes, c).ok() && (c.kind == unit3_wire::Kind::StepMode || c.kind == unit3_wire::Kind::Thread)) {
    for (std::size_t a = 0; a < 3; ++a) (c.kind == unit3_wire::Kind::StepMode ? m.mode : m.thread)[a] = c.digit[a];
    return;
  }
  event({{"type", "reply"}, {"line", line}, {"what", "not understood"}});
}

void Session::step(std::int64_t t) {
  Impl& m = *impl_;
  std::deque<std::unique_ptr<Pending>> work;
  std::array<int, 3> shown{};
  {
    std::lock_guard<std::mutex> l(mu_);
    work.swap(pending_);
    shown = m.shown_thread;
  }
  if (!m.on_bus && m.ep->wait_matched(std::chrono::milliseconds(0))) {
    m.on_bus = true;
    event({{"type", "connection"}, {"what", "unit found on the bus"}});
  }
  if (!m.on_bus) return;
  std::string out;
  for (auto& p : work) {
    for (const auto& line : p->lines) out += line;
    if (p->clear) m.count = {0, 0, 0};  // seed-001.md §7: "0 0 0" zeroes the program's counts
    event({{"type", "sent"}, {"lines", p->lines}});
  }
  const std::vector<std::uint8_t> bytes(out.begin(), out.end());
  std::optional<dds::EchoSample> echo;
  try {
    echo = m.ep->step(bytes, static_cast<std::uint64_t>(t), std::chrono::seconds(2));
  } catch (const dds::Error&) {
    // No answer in 2 s: the unit has left the bus.
  }
  if (!echo) {
    m.on_bus = false;
    event({{"type", "connection"}, {"what", "unit gone from the bus"}});
  } else {
    for (const std::uint8_t byte : echo->bytes) {
      const char ch = static_cast<char>(byte);
      m.rx_rest += ch;
      if (ch == unit3_wire::kEnd) {
        read(m.rx_rest);
        m.rx_rest.clear();
      } else if (m.rx_rest.size() > 64) {
        m.rx_rest.clear();  // no `;` for too long: noise, dropped
      }
    }
  }
  json axes = json::array();
  for (std::size_t a = 0; a < 3; ++a) {
    axes.push_back({{"count", m.count[a]},
                    {"position_um", unit3_axis::position_um(m.count[a], static_cast<std::uint8_t>(shown[a]))},
                    {"mode", m.mode[a]},
                    {"thread", m.thread[a]}});
  }
  pub_.state({{"t_us", t},
              {"on_bus", m.on_bus},
              {"axes", axes},
              {"replies", json(std::vector<std::string>(m.replies.begin(), m.replies.end()))}});
}

}  // namespace ap::unit3_panel
