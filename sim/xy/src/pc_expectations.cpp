// The scenario's expectations (pc_expectations.hpp, docs/sim.md "Expectations"): every subject
// a scenario may name is read here, so the subject table of the docs has one counterpart.
#include "pc_expectations.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <variant>

#include "core/xy/frame/frames.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "sim/text.hpp"
#include "sim/xy/led.hpp"
#include "sim/xy/params.hpp"
#include "pc_board.hpp"
#include "pc_transport.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;

namespace {

using Val = std::variant<std::string, double>;

std::string status_key(xy_codec::EchoStatus s) {
  const auto* i = xy_codec::find_status(static_cast<std::uint32_t>(s));
  return i != nullptr ? std::string(i->key) : "?";
}

std::optional<Val> value(PcContext& pc, BoardPc& b, const std::string& subj, std::int64_t t) {
  auto on = [](bool v) { return Val(std::string(v ? "on" : "off")); };
  const PcMech& mech = pc.mech;
  if (subj.size() > 2 && (subj[0] == 'x' || subj[0] == 'y') && subj[1] == '.') {
    const std::size_t i = subj[0] == 'y' ? 1 : 0;
    const std::string f = subj.substr(2);
    const dds::AxisTelemetry& a = b.tel.axis[i];
    if (f == "pos") return Val(a.pos * mech.um_per_ustep);
    if (f == "target") return Val(a.target * mech.um_per_ustep);
    if (f == "speed") return Val(a.speed * mech.um_per_ustep);
    if (f == "dir") return Val(std::string(a.dir != 0 ? "+" : "-"));
    if (f == "endstop_min") return on(a.endstop_min);
    if (f == "endstop_max") return on(a.endstop_max);
    if (f == "enabled") return on(a.enabled);
    if (f == "blocked") return on(a.blocked);
    if (f == "status") return Val(b.seen.ax[i].have_status ? status_key(b.seen.ax[i].status) : std::string("none"));
    if (f == "lost_steps") return Val(std::stod(env(pc, b, "probe " + subj, t)));
    return std::nullopt;
  }
  if (subj.rfind("board.", 0) == 0) {
    const std::string f = subj.substr(6);
    if (f == "state") {
      static const char* kStates[] = {"blocked", "user", "param"};
      return Val(std::string(b.tel.main_state < 3 ? kStates[b.tel.main_state] : "?"));
    }
    if (f == "led") return Val(led_word(b.tel.led));
    if (f == "ble") {
      // Tab. 7-2 by (S1 | S2 << 1): (0,0) connected, (1,0) standby, (0,1) session, (1,1) shutdown.
      static const char* kBle[] = {"connected", "standby", "session", "shutdown"};
      return Val(std::string(kBle[b.tel.ble_status & 3U]));
    }
    if (f == "charger") return on(b.tel.charger);
    if (f == "usb") return on(b.tel.usb);
    if (f == "low_battery") return on(b.tel.low_battery);
    if (f == "battery") return Val(static_cast<double>(b.tel.battery_mv));
    if (f == "charge_current") return Val(static_cast<double>(b.tel.charge_ma));
    if (f == "temperature") return Val(static_cast<double>(b.tel.temperature_mc));
    if (f == "rotation") return Val(static_cast<double>(b.tel.rotation_mdeg));
    return std::nullopt;
  }
  if (subj.rfind("param.", 0) == 0) {
    const auto id = param_by_name(subj.substr(6));
    const auto it = id ? b.seen.params.find(static_cast<std::uint8_t>(*id)) : b.seen.params.end();
    if (it == b.seen.params.end()) return Val(std::string("none"));
    return Val(static_cast<double>(it->second));
  }
  if (subj.rfind("sub.", 0) == 0) {
    std::string k = subj.substr(4);
    if (k == "charge_current") k = "charge";
    if (k == "temperature") k = "temp";
    const auto it = b.seen.subs.find(k);
    if (it == b.seen.subs.end()) return Val(std::string("none"));
    return Val(static_cast<double>(it->second));
  }
  if (subj == "echo.count") return Val(static_cast<double>(b.seen.echoes));
  if (subj == "echo.x.id" || subj == "echo.y.id") return Val(static_cast<double>(b.seen.ax[subj[5] == 'y' ? 1 : 0].status));
  if (subj == "echo.x.data" || subj == "echo.y.data") return Val(static_cast<double>(b.seen.ax[subj[5] == 'y' ? 1 : 0].data));
  if (subj.rfind("tmc.", 0) == 0 || subj.rfind("fram.", 0) == 0 || subj == "watchdog_stops" || subj == "lost_steps") {
    return Val(std::stod(env(pc, b, "probe " + subj, t)));
  }
  const xy_client::ClientCounters& c = b.client->counters();
  if (subj == "gaps") return Val(static_cast<double>(c.timeouts));
  if (subj == "rejected") return Val(static_cast<double>(c.rejected));
  if (subj == "commands") return Val(static_cast<double>(c.sent));
  if (subj == "echoes") return Val(static_cast<double>(c.answered));
  if (subj == "delivered") return Val(static_cast<double>(c.delivered));
  if (subj == "failed") return Val(static_cast<double>(c.failed));
  if (subj == "retransmissions") return Val(static_cast<double>(c.retransmissions));
  if (subj.rfind("outcome.", 0) == 0) {
    const std::string key = subj.substr(8);
    const std::vector<xy_client::Report>& reports = b.delivery.reports();
    return Val(static_cast<double>(std::count_if(reports.begin(), reports.end(),
                                                 [&](const xy_client::Report& r) { return key == xy_client::to_string(r.outcome); })));
  }
  return std::nullopt;
}

// The scenario language's own comparison (sim/xy/scenario.hpp), on the value with the
// subject's dimension; a word where a number is due (or the reverse) is a failure of the
// expectation, not of the run.
bool compare(const Val& got, const sc::Expectation& e, std::string* why) {
  sc::Value v;
  if (const auto* d = std::get_if<double>(&got)) {
    const auto* want = std::get_if<sc::Quantity>(&e.value);
    v = sc::Quantity{*d, sc::subject_dim(e.subject).value_or(want != nullptr ? want->dim : sc::Dim::none)};
  } else {
    v = std::get<std::string>(got);
  }
  try {
    return sc::holds(e, v);
  } catch (const std::invalid_argument& x) {
    *why = x.what();
    return false;
  }
}

std::string show(const Val& v, const sc::Expectation& e) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  const double d = std::get<double>(v);
  if (const auto* q = std::get_if<sc::Quantity>(&e.value)) {
    const std::string u(sc::unit_name(q->dim));
    return fmt(d) + (u.empty() ? "" : " " + u);
  }
  return fmt(d);
}

}  // namespace

void EchoReadings::echo(const xy_client::EchoEvent& ev) {
  // A rejection echo answers a damaged frame, not the axes: the status shown stays the
  // last one the board reported.
  if (ev.kind != xy_client::EchoKind::Answer && ev.kind != xy_client::EchoKind::Late && ev.kind != xy_client::EchoKind::Resync) {
    return;
  }
  ++echoes;
  for (std::size_t i = 0; i < 2; ++i) {
    const xy_frame::AxisEcho& ae = i == 0 ? ev.echo.x : ev.echo.y;
    ax[i].status = ae.status;
    ax[i].data = ae.data;
    ax[i].have_status = true;
  }
  for (const xy_frame::SubscriberPacket& p : ev.echo.subs) {
    if (p.slot.id == xy_codec::SubscriberId::None) continue;
    if (p.slot.id == xy_codec::SubscriberId::Param) {
      params[p.slot.arg] = p.data;
    } else {
      const auto* info = xy_codec::find_subscriber(static_cast<std::uint32_t>(p.slot.id));
      if (info != nullptr) subs[std::string(info->key)] = p.data;
    }
  }
}

std::vector<std::uint8_t> expected_params(const sc::Scenario& s) {
  std::vector<std::uint8_t> slots;
  for (const sc::Expectation& e : s.expectations) {
    if (e.subject.rfind("param.", 0) == 0) {
      const auto id = param_by_name(e.subject.substr(6));
      if (!id) throw std::runtime_error("unknown parameter in expectation: " + e.subject);
      const auto idx = static_cast<std::uint8_t>(*id);
      if (std::find(slots.begin(), slots.end(), idx) == slots.end()) slots.push_back(idx);
    }
  }
  return slots;
}

Expectations::Expectations(PcContext& pc)
    : pc_(pc), done_(pc.s.boards, std::vector<bool>(pc.s.expectations.size(), false)) {}

std::string Expectations::describe(const sc::Expectation& e, std::uint32_t board) const {
  sc::Scenario one;
  one.name = "x";
  one.duration_us = 1;
  one.expectations.push_back(e);
  std::string text = sc::to_text(one);
  const std::size_t p = text.find("expect ");
  text = p == std::string::npos ? e.subject : text.substr(p);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return pc_.s.name + ".scn:" + std::to_string(e.line) + ": board " + std::to_string(board) + ": " + text;
}

void Expectations::evaluate(BoardPc& b, std::int64_t t, bool at_end) {
  const sc::Scenario& s = pc_.s;
  std::vector<bool>& done = done_[b.id];
  for (std::size_t k = 0; k < s.expectations.size(); ++k) {
    const sc::Expectation& e = s.expectations[k];
    if (!e.target.all && e.target.board != b.id) continue;
    if (done[k]) continue;
    bool check = false;
    switch (e.when) {
      case sc::When::at: check = !at_end && t >= e.t_us; break;
      case sc::When::always: check = !at_end; break;
      case sc::When::between: check = !at_end && t >= e.t_us && t <= e.t2_us; break;
      case sc::When::by: check = !at_end && t <= e.t_us + pc_.opt.step_us - 1; break;
      case sc::When::end: check = at_end; break;
    }
    if (at_end && e.when == sc::When::by && !done[k]) {
      pc_.fail(describe(e, b.id) + ": never held");
      done[k] = true;
      continue;
    }
    if (!check) {
      if (e.when == sc::When::by && t > e.t_us && !done[k]) {
        pc_.fail(describe(e, b.id) + ": did not hold by " + tstr(e.t_us) + " (last value " + last_[k] + ")");
        done[k] = true;
      }
      continue;
    }
    const std::optional<Val> v = value(pc_, b, e.subject, t);
    if (!v) {
      pc_.fail(describe(e, b.id) + ": subject not available in the simulated PC");
      done[k] = true;
      continue;
    }
    std::string why;
    const bool ok = compare(*v, e, &why);
    last_[k] = show(*v, e) + (why.empty() ? "" : " (" + why + ")");
    switch (e.when) {
      case sc::When::at:
      case sc::When::end:
        done[k] = true;
        if (!ok) pc_.fail(describe(e, b.id) + ": got " + last_[k] + " at " + tstr(t));
        break;
      case sc::When::by:
        if (ok) done[k] = true;
        break;
      case sc::When::always:
      case sc::When::between:
        if (!ok) {
          pc_.fail(describe(e, b.id) + ": got " + last_[k] + " at " + tstr(t));
          done[k] = true;   // report the first violation only
        }
        break;
    }
  }
}

}  // namespace ap::sim::xy
