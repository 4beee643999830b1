// The hc08 simulated board and its bus side (sim/hc08/hc08.hpp, docs/hc08-sim.md "The board").
#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>

#include "sim/hc08/hc08.hpp"
#include "sim/serve_loop.hpp"

namespace ap::sim::hc08 {

namespace {

bool digits(const std::string& w, std::size_t max) {
  return !w.empty() && w.size() <= max && w.find_first_not_of("0123456789") == std::string::npos;
}

bool signed_digits(const std::string& w, std::size_t max) {
  return w.size() > 1 && w[0] == '-' ? digits(w.substr(1), max) : digits(w, max);
}

}  // namespace

const char* event_name(Event e) {
  switch (e) {
    case Event::Init: return "init";
    case Event::Scan: return "scan";
    case Event::Key: return "key";
    case Event::Step: return "step";
  }
  return "?";
}

const char* menu_name(std::uint8_t state) {
  static const char* const kNames[] = {"S_DEF", "SET_DRIVE", "SET_DIRECT", "SET_SPEED", "SET_ANGLE", "SET_SPEEDx", "SET_ANGLEx"};
  return state < std::size(kNames) ? kNames[state] : "?";
}

std::int64_t value_of(const Row& r, Quantity q) {
  const hc08_board::Display& d = r.display;
  switch (q) {
    case Quantity::Value: return d.value;
    case Quantity::Point: return d.point;
    case Quantity::Indicator: return d.indicator;
    case Quantity::Mode: return d.k2 && !d.k3 ? 0 : d.k3 && !d.k2 ? 1 : -1;  // -1: both or neither lit
    case Quantity::Drive: return d.drive == '4' ? 4 : d.drive == '8' ? 8 : 0;
    case Quantity::Direction: return d.direction == 'r' ? 1 : d.direction == 'l' ? -1 : 0;
    case Quantity::Error: return d.error ? 1 : 0;
    case Quantity::Adjusted: return d.adjusted ? 1 : 0;
    case Quantity::Running: return r.running ? 1 : 0;
    case Quantity::Steps: return static_cast<std::int64_t>(r.steps);
    case Quantity::Position: return r.position;
    case Quantity::Angle: return (r.position % 80 + 80) % 80 * 45;  // 80 half steps of 4.5° per turn [T Tab. 3.1]
    case Quantity::Frequency: return r.period_ticks > 0 ? (kBusHz + r.period_ticks / 2) / r.period_ticks : 0;
    case Quantity::Period: return r.period_ticks;
    case Quantity::Dir: return r.dir;
    case Quantity::Coils: return r.coils;
    case Quantity::Port: return r.port;
    case Quantity::Presses: return r.presses;
    case Quantity::Unknown: return r.unknown;
  }
  return 0;
}

Board::Board(const BoardOptions& opt) : opt_(opt) { record(Event::Init); }

std::uint8_t Board::scan_level(std::int64_t k) const {
  const auto hold = static_cast<std::int64_t>(key_hold_);
  if (hold == 0 || k < key_first_ || k >= key_first_ + hold) return 0;
  const std::int64_t i = k - key_first_ + 1;  // 1..hold
  if (key_bounce_) {
    // Contact bounce on press and release (seed 002 Fig. 4.2): the first and the last kBounceMs
    // scans of the hold alternate, the first reading the key, the last reading none.
    constexpr auto b = static_cast<std::int64_t>(kBounceMs);
    if (i <= b) return i % 2 == 1 ? key_code_ : 0;
    if (i > hold - b) return (hold - i) % 2 == 1 ? key_code_ : 0;
  }
  return key_code_;
}

void Board::advance_to(std::int64_t t_us) {
  const std::int64_t until = t_us * kUnitsPerUs;
  for (;;) {
    const std::int64_t next_scan = (scans_ + 1) * kUnitsPerMs;
    const bool was_running = unit_.timer_running();
    // The timer restarts its count at each match (and at the start): the next match is one
    // period of BUSCLK after the last (docs/hc08.md "Timer": the period is TMOD + 1 ticks).
    const std::int64_t next_match = was_running ? epoch_ + static_cast<std::int64_t>(unit_.period_ticks()) * kUnitsPerTick
                                                : std::numeric_limits<std::int64_t>::max();
    const std::int64_t t = std::min(next_scan, next_match);
    if (t > until) break;
    now_ = t;
    if (next_match <= next_scan) {
      // The match first when both fall at one instant: the interrupt is pending before the
      // keypad's next scan reads the rows.
      unit_.timer_match();
      epoch_ = t;
      unit_.main_loop();
      // The rotor follows the coils: position and direction from the patterns, not from the
      // core's own counters.
      const int delta = half_steps(rows_.back().coils, coils_of_port(unit_.port()));
      position_ += delta;
      dir_ = static_cast<std::int8_t>(delta > 0 ? 1 : delta < 0 ? -1 : 0);
      period_ = (t - last_step_) / kUnitsPerTick;
      last_step_ = t;
      ++steps_;
      record(Event::Step);
      continue;
    }
    ++scans_;
    const std::uint8_t level = scan_level(scans_);
    const std::uint8_t queued = unit_.queue().size();
    const std::uint32_t dropped = unit_.queue().dropped();
    unit_.key_sample(level);
    const bool pushed = unit_.queue().size() > queued || unit_.queue().dropped() > dropped;
    unit_.main_loop();
    if (!was_running && unit_.timer_running()) {
      epoch_ = t;
      last_step_ = t;
    }
    const std::uint8_t coils = coils_of_port(unit_.port());
    // The coils may move without a step: a drive change at rest (docs/hc08.md "Excitation").
    position_ += half_steps(rows_.back().coils, coils);
    if (pushed) ++presses_;
    const bool changed = level != scan_;
    scan_ = level;
    if (pushed) {
      record(Event::Key);
    } else if (changed || coils != rows_.back().coils || unit_.timer_running() != was_running) {
      record(Event::Scan);
    }
  }
  now_ = std::max(now_, until);
}

void Board::record(Event e) {
  Row r;
  r.t = now_;
  r.event = e;
  r.scan = scan_;
  r.port = unit_.port();
  r.coils = coils_of_port(r.port);
  r.half = unit_.motor().drive() == hc08_drive::Drive::Half;
  r.running = unit_.timer_running();
  r.dir = dir_;
  r.period_ticks = period_;
  r.position = position_;
  r.steps = steps_;
  r.presses = presses_;
  r.unknown = unit_.unknown_keys();
  r.menu = static_cast<std::uint8_t>(unit_.menu().state);
  r.display = unit_.display();
  checker_.check({r.t, e == Event::Step, r.coils, r.half, r.running});
  rows_.push_back(r);
}

std::string Board::press(std::uint8_t code, std::uint32_t hold_ms, bool bounce) {
  if (hold_ms == 0) return "a hold of 0 ms presses nothing";
  if (key_hold_ != 0 && scans_ + 1 < key_first_ + static_cast<std::int64_t>(key_hold_)) {
    return "a key is still held (the scan sees one key at a time)";
  }
  key_first_ = scans_ + 1;  // the first scan after now
  key_hold_ = hold_ms;
  key_code_ = code;
  key_bounce_ = bounce;
  return {};
}

Range Board::range(Quantity q, std::int64_t from_us, std::int64_t to_us, std::int64_t value) const {
  const std::int64_t from = from_us * kUnitsPerUs, to = to_us * kUnitsPerUs;
  // The row in force at `from`: the last at or before it (rows are in time order).
  auto it = std::upper_bound(rows_.begin(), rows_.end(), from, [](std::int64_t t, const Row& r) { return t < r.t; });
  if (it != rows_.begin()) --it;
  Range out;
  bool first = true;
  for (; it != rows_.end() && it->t <= to; ++it) {
    const std::int64_t v = value_of(*it, q);
    out.min = first ? v : std::min(out.min, v);
    out.max = first ? v : std::max(out.max, v);
    first = false;
    ++out.samples;
    out.equal += v == value ? 1U : 0U;
  }
  return out;
}

std::string Board::env(const std::string& line) {
  std::istringstream in(line);
  std::string verb, a1, a2, a3;
  in >> verb >> a1 >> a2 >> a3;
  if (verb == "press") {
    if (!digits(a1, 3) || std::stoul(a1) > 255 || !digits(a2, 6) || (a3 != "0" && a3 != "1")) {
      return "error press CODE HOLD_MS 0|1";
    }
    const std::string why = press(static_cast<std::uint8_t>(std::stoul(a1)), static_cast<std::uint32_t>(std::stoul(a2)), a3 == "1");
    return why.empty() ? "ok" : "error " + why;
  }
  if (verb == "get") {
    Quantity q = Quantity::Value;
    if (!quantity_of(a1, q)) return "error unknown quantity '" + a1 + "'";
    return std::to_string(quantity(q));
  }
  if (verb == "range") {
    Quantity q = Quantity::Value;
    if (!quantity_of(a1, q)) return "error unknown quantity '" + a1 + "'";
    if (!digits(a2, 15) || !signed_digits(a3, 15)) return "error range QUANTITY FROM_US VALUE";
    const Range r = range(q, std::stoll(a2), now_ / kUnitsPerUs, std::stoll(a3));
    std::ostringstream o;
    o << "min=" << r.min << " max=" << r.max << " samples=" << r.samples << " equal=" << r.equal;
    return o.str();
  }
  if (verb == "summary") {
    std::ostringstream o;
    o << "t_us=" << now_ / kUnitsPerUs << " events=" << checker_.events() << " steps=" << steps_ << " presses=" << presses_
      << " dropped=" << unit_.queue().dropped() << " violations=" << checker_.violations().size();
    return o.str();
  }
  if (verb == "violation") return violation_reply(checker_.violations(), a1);
  return "error unknown environment command '" + verb + "'";
}

void Board::finish() { write_board_outputs(opt_.out_dir, rows_); }

int serve_board(const dds::ParticipantPtr& participant, const BoardOptions& opt, std::chrono::milliseconds idle_timeout,
                const std::atomic<bool>* stop) {
  return serve_unit_board<Board>(participant, opt, idle_timeout, stop, [](Board& board, const dds::CommandSample& cmd) {
    // No link to a PC: a plain command only moves the clock; its echo carries no bytes.
    board.advance_to(static_cast<std::int64_t>(cmd.vtime_us));
    return std::vector<std::uint8_t>{};
  });
}

}  // namespace ap::sim::hc08
