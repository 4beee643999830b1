// The XY panel's routes (routes.hpp, docs/panel.md "HTTP"). Every field is checked here and
// named in the 400 reply, so a bad value never reaches the session, let alone the board.
#include "pc/xy/panel/routes.hpp"

namespace ap::xy_panel {

using web::json;

namespace {

json accepted_json(const Accepted& a) { return {{"ok", a.ok}, {"error", a.error}, {"ticket", a.id}}; }
std::pair<int, json> answer(const Accepted& a) { return {a.ok ? 200 : 400, accepted_json(a)}; }

}  // namespace

web::Options web_options(int port) {
  web::Options o;
  o.port = port;
  o.assets_dir = AP_XY_PANEL_ASSETS;
  o.assets = {{"index.html", "text/html; charset=utf-8"},
              {"panel.js", "text/javascript; charset=utf-8"},
              {"panel.css", "text/css; charset=utf-8"}};
  return o;
}

web::Routes routes(Session& s, const std::string& title) {
  web::Routes r;
  r.info = Session::tables();
  r.info["profile"] = "xy";
  r.info["title"] = title;
  r.snapshot = [&s](std::uint64_t after) { return s.snapshot(after); };
  r.posts["command"] = [&s](const json& j) {
    std::string why;
    const auto board = web::int_field(j, "board", 0, 255, why);
    const auto part = board ? web::str_field(j, "part", 8, why) : std::nullopt;
    const auto key = part ? web::str_field(j, "key", 16, why) : std::nullopt;
    const auto data = key ? web::int_field(j, "data", -99'999'999, 99'999'999, why) : std::nullopt;
    if (!data) return web::refused(why);
    return answer(s.submit({static_cast<std::uint32_t>(*board), *part, *key, *data}));
  };
  r.posts["hold"] = [&s](const json& j) {
    std::string why;
    const auto board = web::int_field(j, "board", 0, 255, why);
    const auto axis = board ? web::int_field(j, "axis", 0, 1, why) : std::nullopt;
    const auto level = axis ? web::int_field(j, "level", -2, 2, why) : std::nullopt;
    if (!level) return web::refused(why);
    return answer(s.hold(static_cast<std::uint32_t>(*board), static_cast<int>(*axis), static_cast<int>(*level)));
  };
  r.posts["connect"] = [&s](const json& j) {
    std::string why;
    const auto board = web::int_field(j, "board", 0, 255, why);
    const auto on = board ? web::bool_field(j, "on", why) : std::nullopt;
    if (!on) return web::refused(why);
    return answer(s.connect(static_cast<std::uint32_t>(*board), *on));
  };
  // The developer extension (thesis §8.3): a simulated echo shown as if the board sent it ...
  r.posts["simecho"] = [&s](const json& j) {
    std::string why;
    const auto board = web::int_field(j, "board", 0, 255, why);
    const auto status = board ? web::str_field(j, "status", 16, why) : std::nullopt;
    const auto data = status ? web::int_field(j, "data", -99'999'999, 99'999'999, why) : std::nullopt;
    if (!data) return web::refused(why);
    return answer(s.simulate_echo(static_cast<std::uint32_t>(*board), *status, static_cast<std::int32_t>(*data)));
  };
  // ... and the simulated board's environment commands (docs/sim.md).
  r.posts["env"] = [&s](const json& j) {
    std::string why;
    const auto board = web::int_field(j, "board", 0, 255, why);
    const auto line = board ? web::str_field(j, "line", 64, why) : std::nullopt;
    if (!line) return web::refused(why);
    const std::string rep = s.env(static_cast<std::uint32_t>(*board), *line);
    const bool ok = rep.rfind("ok", 0) == 0;
    return std::pair<int, json>{ok ? 200 : 400, {{"ok", ok}, {"reply", rep}}};
  };
  return r;
}

}  // namespace ap::xy_panel
