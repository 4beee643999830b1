#include "models/unit3/pc_view.hpp"

#include <cstdio>

namespace ap::model::unit3 {

namespace {

// Endstop bit 2a is axis a's minimum end, 2a + 1 its maximum (docs/unit3.md "The board").
bool closed(std::uint8_t endstops, std::size_t axis, int dir) {
  return ((endstops >> (2U * axis + (dir > 0 ? 1U : 0U))) & 1U) != 0;
}

bool digit(char c) { return c >= '0' && c <= '9'; }

std::string error(int code) {
  char b[8];
  std::snprintf(b, sizeof b, "E%02d;", code);
  return b;
}

// The line rules of docs/unit3.md "The wire", in the order the table states them: first byte,
// length, then each field. Returns 0 for a good line.
int check(const std::string& l) {
  const char k = l[0];
  const std::string kinds = "DXYZMTCG";
  if (kinds.find(k) == std::string::npos) return 1;
  const std::size_t want = (k == 'X' || k == 'Y' || k == 'Z') ? 17 : (k == 'C' || k == 'G') ? 2 : 5;
  if (l.size() != want) return 2;
  for (std::size_t i = 1; i + 1 < l.size(); ++i) {
    const char c = l[i];
    if (k == 'D') {
      if (c != '+' && c != '-') return 4;
    } else if (!digit(c)) {
      return 3;
    } else if (k == 'M' && c > '5') {
      return 5;
    } else if (k == 'T' && c > '6') {
      return 6;
    }
  }
  return 0;
}

}  // namespace

std::string PcView::report(int axis, std::int64_t count) {
  char b[32];
  const unsigned long long mag = static_cast<unsigned long long>(count < 0 ? -count : count);
  std::snprintf(b, sizeof b, "%c%c%018llu;", "XYZ"[axis], count < 0 ? '-' : '+', mag);
  return b;
}

std::vector<std::string> PcView::receive(const std::string& bytes, std::uint8_t endstops) {
  std::vector<std::string> out;
  for (const char c : bytes) {
    if (dropping_) {
      if (c == ';') dropping_ = false;
      continue;
    }
    if (pending_.empty() && (c == '\r' || c == '\n' || c == ' ' || c == '\t')) continue;
    if (pending_.size() == 17) {  // the longest command is 17 bytes: an 18th is too long
      out.push_back(error(7));
      pending_.clear();
      dropping_ = c != ';';
      continue;
    }
    pending_ += c;
    if (c != ';') continue;
    for (auto& r : line(pending_, endstops)) out.push_back(r);
    pending_.clear();
  }
  return out;
}

std::vector<std::string> PcView::settings_replies(const Settings& s) {
  std::string m = "M", t = "T";
  for (int a = 0; a < 3; ++a) {
    m += static_cast<char>('0' + s.mode[static_cast<std::size_t>(a)]);
    t += static_cast<char>('0' + s.thread[static_cast<std::size_t>(a)]);
  }
  return {m + ";", t + ";"};
}

std::vector<std::string> PcView::zero() {
  std::vector<std::string> out;
  for (int a = 0; a < 3; ++a) {
    axes_[static_cast<std::size_t>(a)].counter = 0;
    out.push_back(report(a, 0));
  }
  return out;
}

std::vector<std::string> PcView::line(const std::string& l, std::uint8_t endstops) {
  if (const int e = check(l)) return {error(e)};
  switch (l[0]) {
    case 'D':
      for (std::size_t a = 0; a < 3; ++a) latched_[a] = l[1 + a] == '+' ? 1 : -1;
      return {};
    case 'M':
    case 'T':
      for (std::size_t a = 0; a < 3; ++a) (l[0] == 'M' ? settings_.mode : settings_.thread)[a] = l[1 + a] - '0';
      stored_ = settings_;
      return settings_replies(settings_);
    case 'C': return zero();
    case 'G': return settings_replies(stored_);  // G reads the EEPROM [T §2.3]: not a menu edit before its Back
    default: break;
  }
  const auto ai = static_cast<std::size_t>(l[0] - 'X');
  Axis& ax = axes_[ai];
  if (ax.remaining > 0 || ax.running) return {error(20)};
  const int dir = latched_[ai];
  if (closed(endstops, ai, dir)) return {error(23)};
  ax.mode = settings_.mode[ai];
  std::uint64_t count = 0;
  for (std::size_t i = 1; i <= 15; ++i) count = count * 10 + static_cast<std::uint64_t>(l[i] - '0');
  const std::uint64_t per = 32U >> ax.mode;
  if (count % per != 0) return {error(21)};
  const std::int64_t target = ax.counter + (dir > 0 ? 1 : -1) * static_cast<std::int64_t>(count);
  if (target > 999'999'999'999'999'999LL || target < -999'999'999'999'999'999LL) return {error(22)};
  if (count == 0) return {report(static_cast<int>(ai), ax.counter)};
  ax.remaining = count / per;
  ax.move_dir = dir;
  return {};
}

std::vector<std::string> PcView::press(int button) {
  enum { Enter, Back, Up, Down, Left, Right };
  switch (window_) {
    case 0:
      if (button == Enter) {
        window_ = 1;
        item_ = 0;
      }
      return {};
    case 1:
      if (button == Up && item_ > 0) --item_;
      if (button == Down && item_ < 2) ++item_;
      if (button == Back) window_ = 0;
      if (button == Enter) {
        if (item_ == 2) return zero();
        window_ = item_ == 0 ? 2 : 3;
        sel_ = 0;
      }
      return {};
    default: {
      auto& v = (window_ == 2 ? settings_.mode : settings_.thread)[static_cast<std::size_t>(sel_)];
      const int max = window_ == 2 ? 5 : 6;
      if (button == Up && sel_ > 0) --sel_;
      if (button == Down && sel_ < 2) ++sel_;
      if (button == Left && v > 0) --v;
      if (button == Right && v < max) ++v;
      if (button == Back) {
        window_ = 1;
        stored_ = settings_;
        return settings_replies(settings_);
      }
      return {};
    }
  }
}

bool PcView::tick(const Pins& p, std::uint8_t endstops, std::vector<int>& stopped, std::vector<int>& cut, std::string& why) {
  for (int a = 0; a < 3; ++a) {
    Axis& ax = axes_[static_cast<std::size_t>(a)];
    const auto ua = static_cast<std::size_t>(a);
    if (!ax.running && ax.remaining == 0) ax.mode = settings_.mode[ua];  // the unit sets MODE at rest
    const bool towards_closed = closed(endstops, ua, p.dir[ua]);
    if (ax.remaining > 0 && closed(endstops, ua, ax.move_dir)) {
      ax.remaining = 0;  // the endstop ends the move in the tick it is seen
      cut.push_back(a);
    }
    if (p.pulses[ua] > 0) {
      if (towards_closed) {
        why = std::string("a pulse of ") + "XYZ"[a] + " towards its closed endstop";
        return false;
      }
      if (p.pulses[ua] > 1) {
        why = "more than one pulse in a tick";
        return false;
      }
      if (ax.remaining > 0 && p.dir[ua] != ax.move_dir) {
        why = std::string("a PC move of ") + "XYZ"[a] + " pulsed against its direction";
        return false;
      }
      ax.counter += p.dir[ua] * static_cast<std::int64_t>(32 >> ax.mode);
      if (ax.remaining > 0 && --ax.remaining == 0) stopped.push_back(a);
    }
    // The stick drives only in the POSITIONS window (docs/unit3.md "The menu"): an axis with no
    // PC move may start there only (stopping in the other windows is timing, the unit's).
    if (!ax.running && ax.remaining == 0 && p.running[ua] && window_ != 0) {
      why = std::string("the stick started ") + "XYZ"[a] + " outside the POSITIONS window";
      return false;
    }
    ax.running = p.running[ua];
    if (ax.remaining > 0 && !ax.running) {
      why = std::string("a PC move of ") + "XYZ"[a] + " stopped before its count";
      return false;
    }
    if (!ax.running && ax.remaining == 0) ax.mode = settings_.mode[ua];  // at rest the pins follow the settings
  }
  return true;
}

void PcView::power_cycle() {
  settings_ = stored_;
  for (auto& ax : axes_) ax = Axis{};
  latched_ = {1, 1, 1};  // D is not stored: + after power-up (docs/unit3.md "The board")
  for (std::size_t a = 0; a < 3; ++a) axes_[a].mode = settings_.mode[a];
  pending_.clear();
  dropping_ = false;
  window_ = item_ = sel_ = 0;
}

}  // namespace ap::model::unit3
