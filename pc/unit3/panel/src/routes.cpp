// The unit3 panel's routes (routes.hpp): Send with three displacements (µm), step modes and
// threads, each an integer array of three checked here; "0 0 0".
#include "pc/unit3/panel/routes.hpp"

#include <optional>

namespace ap::unit3_panel {

using web::json;

namespace {

std::optional<std::array<std::int64_t, 3>> three(const json& j, const char* name, std::int64_t lo, std::int64_t hi, std::string& why) {
  if (!j.contains(name) || !j[name].is_array() || j[name].size() != 3) {
    why = std::string("field '") + name + "' is not an array of three values";
    return std::nullopt;
  }
  std::array<std::int64_t, 3> v{};
  for (std::size_t a = 0; a < 3; ++a) {
    const auto x = web::int_field(json{{name, j[name][a]}}, name, lo, hi, why);
    if (!x) {
      why = std::string(a == 0 ? "X" : (a == 1 ? "Y" : "Z")) + ": " + why;
      return std::nullopt;
    }
    v[a] = *x;
  }
  return v;
}

json sent_json(const Sent& s) {
  json c = json::array();
  for (const auto& k : s.conversions) {
    c.push_back({{"ok", k.ok}, {"sign", k.sign}, {"steps", k.steps}, {"count", k.count}, {"achieved_um", k.achieved_um}});
  }
  return {{"ok", s.ok}, {"error", s.error}, {"lines", s.lines}, {"conversions", c}};
}

}  // namespace

web::Options web_options(int port) {
  web::Options o;
  o.port = port;
  o.assets_dir = AP_UNIT3_PANEL_ASSETS;
  o.assets = {{"index.html", "text/html; charset=utf-8"}, {"unit3.js", "text/javascript; charset=utf-8"},
              {"unit3.css", "text/css; charset=utf-8"}};
  return o;
}

web::Routes routes(Session& s, const std::string& title) {
  web::Routes r;
  r.info = Session::tables();
  r.info["profile"] = "unit3";
  r.info["title"] = title;
  r.snapshot = [&s](std::uint64_t after) { return s.snapshot(after); };
  r.posts["send"] = [&s](const json& j) {
    std::string why;
    const auto um = three(j, "um", -kMaxDisplacementUm, kMaxDisplacementUm, why);
    const auto mode = um ? three(j, "mode", 0, 5, why) : std::nullopt;
    const auto thread = mode ? three(j, "thread", 0, 6, why) : std::nullopt;
    if (!thread) return web::refused(why);
    SendRequest q;
    for (std::size_t a = 0; a < 3; ++a) {
      q.um[a] = (*um)[a];
      q.mode[a] = static_cast<std::uint8_t>((*mode)[a]);
      q.thread[a] = static_cast<std::uint8_t>((*thread)[a]);
    }
    const Sent sent = s.send(q);
    return std::pair<int, json>{sent.ok ? 200 : 400, sent_json(sent)};
  };
  r.posts["clear"] = [&s](const json&) { return std::pair<int, json>{200, sent_json(s.clear())}; };
  r.posts["get"] = [&s](const json&) { return std::pair<int, json>{200, sent_json(s.get_settings())}; };
  return r;
}

}  // namespace ap::unit3_panel
