// The panel's HTTP routes (server.hpp, docs/panel.md "HTTP"). A request body is JSON of at
// most 1 KiB; every field is checked for its type and range here and named in the 400 reply,
// so a bad value never reaches the session, let alone the board.
#include "pc/xy/panel/server.hpp"

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

namespace ap::xy_panel {

using json = nlohmann::json;

namespace {

constexpr std::size_t kMaxBody = 1024;

// Requests answered 400: the browser tests read it to tell a value the page refused (never
// sent) from one the server refused.
std::atomic<std::uint64_t> g_refused{0};

std::optional<std::string> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void reply(httplib::Response& res, int status, const json& body) {
  if (status == 400) ++g_refused;
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void bad(httplib::Response& res, const std::string& why) { reply(res, 400, {{"ok", false}, {"error", why}}); }

// The body as a JSON object, else the reason it is not one.
std::optional<json> body_of(const httplib::Request& req, httplib::Response& res) {
  if (req.body.size() > kMaxBody) {
    bad(res, "request body over " + std::to_string(kMaxBody) + " bytes");
    return std::nullopt;
  }
  json j = json::parse(req.body, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    bad(res, "request body is not a JSON object");
    return std::nullopt;
  }
  return j;
}

// An integer field in [lo, hi]; the reason otherwise (a string of digits is refused too: the
// page sends numbers, and a field it could not turn into one is its error to show).
std::optional<std::int64_t> int_field(const json& j, const char* name, std::int64_t lo, std::int64_t hi, std::string& why) {
  if (!j.contains(name)) {
    why = std::string("missing field '") + name + "'";
    return std::nullopt;
  }
  const json& v = j[name];
  if (!v.is_number_integer()) {
    why = std::string("field '") + name + "' is not an integer";
    return std::nullopt;
  }
  const std::int64_t x = v.get<std::int64_t>();
  if (x < lo || x > hi) {
    why = std::string("field '") + name + "' = " + std::to_string(x) + " outside " + std::to_string(lo) + ".." + std::to_string(hi);
    return std::nullopt;
  }
  return x;
}

std::optional<std::string> str_field(const json& j, const char* name, std::size_t max_len, std::string& why) {
  if (!j.contains(name) || !j[name].is_string()) {
    why = std::string("field '") + name + "' is not a string";
    return std::nullopt;
  }
  std::string s = j[name].get<std::string>();
  if (s.size() > max_len) {
    why = std::string("field '") + name + "' longer than " + std::to_string(max_len) + " characters";
    return std::nullopt;
  }
  return s;
}

json accepted_json(const Accepted& a) { return {{"ok", a.ok}, {"error", a.error}, {"ticket", a.id}}; }

}  // namespace

bool serve(Session& s, const ServerOptions& o, const std::function<void(int port)>& ready,
           const std::function<bool()>& stopped) {
  httplib::Server http;
  http.set_payload_max_length(kMaxBody * 4);

  const auto asset = [&](const std::string& name, const char* type) {
    http.Get("/" + (name == "index.html" ? std::string() : name), [&o, name, type](const httplib::Request&, httplib::Response& res) {
      const auto text = read_file(o.assets_dir + "/" + name);
      if (!text) {
        res.status = 404;
        res.set_content("missing asset " + name, "text/plain");
        return;
      }
      res.set_content(*text, type);
    });
  };
  asset("index.html", "text/html; charset=utf-8");
  asset("panel.js", "text/javascript; charset=utf-8");
  asset("panel.css", "text/css; charset=utf-8");

  http.Get("/api/info", [&](const httplib::Request&, httplib::Response& res) {
    json t = Session::tables();
    t["profile"] = o.profile;
    t["title"] = o.title;
    reply(res, 200, t);
  });
  http.Get("/api/state", [&](const httplib::Request& req, httplib::Response& res) {
    std::uint64_t after = 0;
    if (req.has_param("after")) after = std::strtoull(req.get_param_value("after").c_str(), nullptr, 10);
    json snap = s.snapshot(after);
    snap["refused_requests"] = g_refused.load();
    reply(res, 200, snap);
  });
  // The push channel: the state every 100 ms with the events since the last message.
  http.Get("/api/events", [&](const httplib::Request&, httplib::Response& res) {
    auto last = std::make_shared<std::uint64_t>(0);
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider("text/event-stream", [&s, &stopped, last](std::size_t, httplib::DataSink& sink) {
      if (stopped()) return false;
      json snap = s.snapshot(*last);
      for (const auto& e : snap["events"]) *last = std::max(*last, e["id"].get<std::uint64_t>());
      const std::string msg = "data: " + snap.dump() + "\n\n";
      if (!sink.write(msg.data(), msg.size())) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      return true;
    });
  });
  http.Post("/api/command", [&](const httplib::Request& req, httplib::Response& res) {
    const auto j = body_of(req, res);
    if (!j) return;
    std::string why;
    const auto board = int_field(*j, "board", 0, 255, why);
    const auto part = board ? str_field(*j, "part", 8, why) : std::nullopt;
    const auto key = part ? str_field(*j, "key", 16, why) : std::nullopt;
    const auto data = key ? int_field(*j, "data", -99'999'999, 99'999'999, why) : std::nullopt;
    if (!data) return bad(res, why);
    const Accepted a = s.submit({static_cast<std::uint32_t>(*board), *part, *key, *data});
    reply(res, a.ok ? 200 : 400, accepted_json(a));
  });
  http.Post("/api/hold", [&](const httplib::Request& req, httplib::Response& res) {
    const auto j = body_of(req, res);
    if (!j) return;
    std::string why;
    const auto board = int_field(*j, "board", 0, 255, why);
    const auto axis = board ? int_field(*j, "axis", 0, 1, why) : std::nullopt;
    const auto level = axis ? int_field(*j, "level", -2, 2, why) : std::nullopt;
    if (!level) return bad(res, why);
    const Accepted a = s.hold(static_cast<std::uint32_t>(*board), static_cast<int>(*axis), static_cast<int>(*level));
    reply(res, a.ok ? 200 : 400, accepted_json(a));
  });
  http.Post("/api/connect", [&](const httplib::Request& req, httplib::Response& res) {
    const auto j = body_of(req, res);
    if (!j) return;
    std::string why;
    const auto board = int_field(*j, "board", 0, 255, why);
    if (!board) return bad(res, why);
    if (!j->contains("on") || !(*j)["on"].is_boolean()) return bad(res, "field 'on' is not true or false");
    const Accepted a = s.connect(static_cast<std::uint32_t>(*board), (*j)["on"].get<bool>());
    reply(res, a.ok ? 200 : 400, accepted_json(a));
  });
  http.Post("/api/simecho", [&](const httplib::Request& req, httplib::Response& res) {
    const auto j = body_of(req, res);
    if (!j) return;
    std::string why;
    const auto board = int_field(*j, "board", 0, 255, why);
    const auto status = board ? str_field(*j, "status", 16, why) : std::nullopt;
    const auto data = status ? int_field(*j, "data", -99'999'999, 99'999'999, why) : std::nullopt;
    if (!data) return bad(res, why);
    const Accepted a = s.simulate_echo(static_cast<std::uint32_t>(*board), *status, static_cast<std::int32_t>(*data));
    reply(res, a.ok ? 200 : 400, accepted_json(a));
  });
  // The developer extension (thesis §8.3): the simulated board's environment commands.
  http.Post("/api/env", [&](const httplib::Request& req, httplib::Response& res) {
    const auto j = body_of(req, res);
    if (!j) return;
    std::string why;
    const auto board = int_field(*j, "board", 0, 255, why);
    const auto line = board ? str_field(*j, "line", 64, why) : std::nullopt;
    if (!line) return bad(res, why);
    const std::string r = s.env(static_cast<std::uint32_t>(*board), *line);
    reply(res, r.rfind("ok", 0) == 0 ? 200 : 400, {{"ok", r.rfind("ok", 0) == 0}, {"reply", r}});
  });

  int port = o.port;
  if (port == 0) {
    port = http.bind_to_any_port(o.host);
    if (port < 0) return false;
  } else if (!http.bind_to_port(o.host, port)) {
    return false;
  }
  std::thread watcher([&] {
    while (!stopped()) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    http.stop();
  });
  ready(port);
  http.listen_after_bind();
  watcher.join();
  return true;
}

}  // namespace ap::xy_panel
