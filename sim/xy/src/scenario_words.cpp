// The tables of the XY scenario language (docs/scenarios.md): its units and dimensions
// ("Lexical rules"), its verbs ("Actions") and its subjects ("Expectations"), apart from the
// statements that use them (scenario.cpp) so the parser and the printer share one copy.
#include "scenario_words.hpp"

#include <algorithm>
#include <string>

namespace ap::sim::xy::scenario {
namespace {

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

}  // namespace

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

std::optional<Verb> verb_of(std::string_view words) {
  const auto it = std::find_if(kVerbs.begin(), kVerbs.end(), [&](const Verbs& x) { return x.name == words; });
  if (it == kVerbs.end()) return std::nullopt;
  return it->verb;
}

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

}  // namespace ap::sim::xy::scenario
