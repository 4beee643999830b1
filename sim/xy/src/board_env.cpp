// The simulated board's text commands (docs/sim.md "The simulated board", docs/scenarios.md):
// env() reads one line of the harness's environment (battery, charger, pins, setup before
// boot, reboot, the platform's turn) or a probe of the board and its models (`probe NAME`:
// driver fields, the FRAM's stored set, lost steps, the echo and delivery checks' figures),
// and answers "ok[ VALUE]" or "err WHY". The scenario language's names for parameters and the
// LED's words are here too.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/xy/storage/parameters.hpp"
#include "core/xy/tmc2130/fields.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/xy/board.hpp"
#include "sim/xy/led.hpp"
#include "sim/xy/outcome_oracle.hpp"
#include "sim/xy/params.hpp"

namespace ap::sim::xy {
namespace {

namespace tmc = ap::xy_tmc2130;

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  std::string t;
  while (in >> t) w.push_back(t);
  return w;
}

std::int64_t to_int(const std::string& s) {
  std::size_t n = 0;
  const long long v = std::stoll(s, &n);
  if (n != s.size()) throw std::invalid_argument("not an integer: " + s);
  return v;
}

std::size_t axis_of(const std::string& s) {
  if (s == "x") return 0;
  if (s == "y") return 1;
  throw std::invalid_argument("axis must be x or y: " + s);
}

}  // namespace

std::optional<xy_storage::ParamId> param_by_name(std::string_view name) {
  struct Alias {
    std::string_view name;
    xy_storage::ParamId id;
  };
  static constexpr Alias kAliases[] = {
      {"accel", xy_storage::ParamId::MaxAcceleration},  {"speed_fast", xy_storage::ParamId::FastSpeed},
      {"speed_slow", xy_storage::ParamId::SlowSpeed},     {"speed_start", xy_storage::ParamId::StartSpeed},
      {"lead", xy_storage::ParamId::LeadPitch},           {"steps", xy_storage::ParamId::StepsPerRev},
      {"irun", xy_storage::ParamId::RunCurrent},          {"ihold", xy_storage::ParamId::HoldCurrent},
  };
  for (const Alias& a : kAliases) {
    if (a.name == name) return a.id;
  }
  for (const xy_storage::MapEntry& e : xy_storage::kItemMap) {
    if (e.name == name && e.role != xy_storage::Role::Meta) return e.id;
  }
  return std::nullopt;
}

std::string led_word(std::uint8_t code) {
  static constexpr std::string_view kColours[] = {"off", "red", "green", "yellow", "blue", "magenta", "cyan", "white"};
  static constexpr std::string_view kBlink[] = {"", "_slow", "_fast", "_fast"};
  std::string w(kColours[code & 7U]);
  w.append(kBlink[(code >> 4) & 3U]);
  return w;
}

std::string SimBoard::probe(const std::string& subject) {
  if (subject.rfind("tmc.", 0) == 0 && subject.size() > 6) {
    const std::size_t a = axis_of(subject.substr(4, 1));
    const std::string field = subject.substr(6);
    for (const tmc::FieldInfo& f : tmc::kFields) {
      if (f.name == field) return std::to_string(tmc::field_get(parts_.tmc[a].chip_register(f.reg), f.field));
    }
    throw std::invalid_argument("unknown TMC2130 field " + field);
  }
  if (subject.rfind("fram.", 0) == 0) {
    const auto id = param_by_name(subject.substr(5));
    if (!id) throw std::invalid_argument("unknown parameter " + subject.substr(5));
    // What a fresh boot would load: a copy of the chip, read by a store of its own.
    return std::to_string(*xy_storage::get_field(model::xy_echo::stored_set(parts_.fram), *id));
  }
  if (subject == "x.lost_steps" || subject == "y.lost_steps") return std::to_string(lost_step_risks(axis_of(subject.substr(0, 1))));
  if (subject == "lost_steps") return std::to_string(lost_step_risks(0) + lost_step_risks(1));
  if (subject == "watchdog_stops") return std::to_string(board_->counters().watchdog_expiries);
  if (subject.rfind("fate.", 0) == 0) {
    // fate.SEQ: the last frame taken with that seq, as sim/xy/outcome_oracle.hpp writes it.
    const auto it = fates_.find(static_cast<std::uint16_t>(to_int(subject.substr(5))));
    return it == fates_.end() ? std::string("none") : fate_text(it->second);
  }
  if (subject == "taken") return std::to_string(frames_taken_) + " " + std::to_string(taken_digest_);
  if (subject == "gated") return std::to_string(board_->counters().gated_frames);
  if (subject == "violations") {
    std::string s = std::to_string(violations_.size());
    if (!violations_.empty()) {
      const Violation& v = violations_.front();
      s += " first at " + std::to_string(v.t_us) + " us, axis " + std::to_string(v.axis) + ": " + v.what;
    }
    return s;
  }
  if (subject == "echo_model") {
    // "CHECKED BAD": echoes compared with the model, disagreements.
    return std::to_string(echoes_checked_) + " " + std::to_string(echo_bad_count_);
  }
  if (subject.rfind("echo_model.", 0) == 0) {
    // echo_model.K.OFF: 100 characters of the K-th kept disagreement from OFF (a bus reply
    // carries at most dds::kFrameMax bytes), empty past its end.
    const std::string rest = subject.substr(11);
    const std::size_t dot = rest.find('.');
    if (dot == std::string::npos) throw std::invalid_argument("probe echo_model.K.OFF");
    const auto k = static_cast<std::size_t>(to_int(rest.substr(0, dot)));
    const auto off = static_cast<std::size_t>(to_int(rest.substr(dot + 1)));
    if (k >= echo_bad_.size()) throw std::invalid_argument("no disagreement " + rest.substr(0, dot));
    return off < echo_bad_[k].size() ? echo_bad_[k].substr(off, 100) : std::string();
  }
  if (subject.rfind("echo_sent.", 0) == 0) {
    // echo_sent.N: "TOTAL DIGEST_N QUEUED": echoes the core sent, the digest of the TX stream
    // after the first N of them, and the echoes still waiting in the TX queue.
    const auto n = static_cast<std::size_t>(to_int(subject.substr(10)));
    if (n > echo_digests_.size()) throw std::invalid_argument("only " + std::to_string(echo_digests_.size()) + " echoes sent");
    return std::to_string(echo_digests_.size()) + " " + std::to_string(n == 0 ? kFnvBasis : echo_digests_[n - 1]) + " " +
           std::to_string(tx_.size() / xy_codec::kEchoLength);
  }
  if (subject == "carriage.x" || subject == "carriage.y") {
    return std::to_string(static_cast<long long>(std::llround(carriage_um_[axis_of(subject.substr(9))])));
  }
  throw std::invalid_argument("unknown probe " + subject);
}

std::string SimBoard::env(const std::string& line) {
  try {
    const std::vector<std::string> w = words(line);
    if (w.empty()) return "err empty";
    const std::string& k = w[0];
    auto need = [&](std::size_t n) {
      if (w.size() != n) throw std::invalid_argument("'" + k + "' takes " + std::to_string(n - 1) + " arguments");
    };
    auto preboot = [&] {
      if (board_) throw std::invalid_argument("'" + k + "' is a setup command (before boot)");
    };
    if (k == "probe") {
      need(2);
      if (!board_) boot();
      return "ok " + probe(w[1]);
    }
    if (k == "pos") {
      need(3);
      preboot();
      carriage_um_[axis_of(w[1])] = static_cast<double>(to_int(w[2]));
    } else if (k == "endstop_at") {
      need(4);
      const std::size_t a = axis_of(w[1]);
      (w[2] == "min" ? endstop_min_um_ : endstop_max_um_)[a] = static_cast<std::int32_t>(to_int(w[3]));
    } else if (k == "param" || k == "fram") {
      need(3);
      preboot();
      if (!param_by_name(w[1])) throw std::invalid_argument("unknown parameter " + w[1]);
      preboot_params_.emplace_back(w[1], to_int(w[2]));
    } else if (k == "boot") {
      need(1);
      if (!board_) boot();
    } else if (k == "battery") {
      need(2);
      battery_mv_ = static_cast<std::uint16_t>(std::clamp<std::int64_t>(to_int(w[1]), 0, 65535));
    } else if (k == "charger" || k == "usb") {
      need(2);
      (k == "charger" ? charger_ : usb_) = to_int(w[1]) != 0;
    } else if (k == "temperature") {
      need(2);
      parts_.tmp117.chip.set_temperature_mc(static_cast<std::int32_t>(std::clamp<std::int64_t>(to_int(w[1]), -300'000, 300'000)));
    } else if (k == "rotate") {
      need(2);
      // The shorter way from where the turn stands now (the board's frame: 0 at its power-up)
      // to the angle asked for; a half turn goes forward.
      const std::int64_t want = ((to_int(w[1]) % 360'000) + 360'000) % 360'000;
      const std::int64_t now = ((turned_codes_ / kGyroLsbPerDps) % 360'000 + 360'000) % 360'000;
      std::int64_t delta = (want - now + 360'000) % 360'000;
      if (delta > 180'000) delta -= 360'000;
      turn_to_codes_ = turned_codes_ + delta * kGyroLsbPerDps;
    } else if (k == "ble") {
      need(2);
      if (w[1] == "shutdown") ble_ = Ble::Shutdown;
      else if (w[1] == "standby") ble_ = Ble::Standby;
      else if (w[1] == "connected") ble_ = Ble::Connected;
      else if (w[1] == "session") ble_ = Ble::Session;
      else throw std::invalid_argument("BLE state " + w[1]);
    } else if (k == "endstop") {
      need(4);
      const std::size_t a = axis_of(w[1]);
      const std::size_t side = w[2] == "min" ? 0 : 1;
      endstop_force_[a][side] = w[3] == "on" ? std::int8_t{1} : (w[3] == "off" ? std::int8_t{-1} : std::int8_t{0});
    } else if (k == "button") {
      need(2);
      button_ = true;
      button_until_us_ = now_us_ + (w[1] == "hold" ? 3'000'000 : 200'000);
    } else if (k == "reboot") {
      need(1);
      parts_.power_cycle();
      powered_off_ = false;
      if (board_) boot();
    } else if (k == "encoder") {
      need(2);
      if (w[1] != "on" && w[1] != "off") throw std::invalid_argument("encoder on|off");
      encoder_fitted_ = w[1] == "on";
    } else {
      return "err unknown environment command '" + k + "'";
    }
    return "ok";
  } catch (const std::exception& e) {
    return std::string("err ") + e.what();
  }
}

}  // namespace ap::sim::xy
