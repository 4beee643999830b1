// The panels' HTTP server (server.hpp, docs/panel.md "HTTP").
#include "pc/web/server.hpp"

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

namespace ap::web {

namespace {

constexpr std::size_t kMaxBody = 1024;

std::optional<std::string> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::pair<int, json> refused(const std::string& why) { return {400, {{"ok", false}, {"error", why}}}; }

std::optional<std::int64_t> int_field(const json& j, const char* name, std::int64_t lo, std::int64_t hi, std::string& why) {
  if (!j.contains(name)) {
    why = std::string("missing field '") + name + "'";
    return std::nullopt;
  }
  // A string of digits is refused too: the page sends numbers, and a field it could not turn
  // into one is its error to show.
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

std::optional<bool> bool_field(const json& j, const char* name, std::string& why) {
  if (!j.contains(name) || !j[name].is_boolean()) {
    why = std::string("field '") + name + "' is not true or false";
    return std::nullopt;
  }
  return j[name].get<bool>();
}

bool serve(const Routes& r, const Options& o, const std::function<void(int port)>& ready,
           const std::function<bool()>& stopped) {
  httplib::Server http;
  http.set_payload_max_length(kMaxBody * 4);
  // Requests answered 400: the browser tests read it to tell a value the page refused (never
  // sent) from one the server refused.
  auto refusals = std::make_shared<std::atomic<std::uint64_t>>(0);
  const auto reply = [refusals](httplib::Response& res, int status, const json& body) {
    if (status == 400) ++*refusals;
    res.status = status;
    res.set_content(body.dump(), "application/json");
  };

  for (const auto& [name, type] : o.assets) {
    http.Get("/" + (name == "index.html" ? std::string() : name), [&o, name = name, type = type](const httplib::Request&, httplib::Response& res) {
      const auto text = read_file(o.assets_dir + "/" + name);
      if (!text) {
        res.status = 404;
        res.set_content("missing asset " + name, "text/plain");
        return;
      }
      res.set_content(*text, type);
    });
  }
  http.Get("/api/info", [&](const httplib::Request&, httplib::Response& res) { reply(res, 200, r.info); });
  http.Get("/api/state", [&](const httplib::Request& req, httplib::Response& res) {
    std::uint64_t after = 0;
    if (req.has_param("after")) after = std::strtoull(req.get_param_value("after").c_str(), nullptr, 10);
    json snap = r.snapshot(after);
    snap["refused_requests"] = refusals->load();
    reply(res, 200, snap);
  });
  http.Get("/api/events", [&](const httplib::Request&, httplib::Response& res) {
    auto last = std::make_shared<std::uint64_t>(0);
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider("text/event-stream", [&r, &stopped, last](std::size_t, httplib::DataSink& sink) {
      if (stopped()) return false;
      json snap = r.snapshot(*last);
      for (const auto& e : snap["events"]) *last = std::max(*last, e["id"].get<std::uint64_t>());
      const std::string msg = "data: " + snap.dump() + "\n\n";
      if (!sink.write(msg.data(), msg.size())) return false;  // the tab is gone
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      return true;
    });
  });
  for (const auto& [key, handler] : r.posts) {
    http.Post("/api/" + key, [&reply, h = handler](const httplib::Request& req, httplib::Response& res) {
      if (req.body.size() > kMaxBody) {
        const auto [s, b] = refused("request body over " + std::to_string(kMaxBody) + " bytes");
        return reply(res, s, b);
      }
      json j = json::parse(req.body, nullptr, false);
      if (j.is_discarded() || !j.is_object()) {
        const auto [s, b] = refused("request body is not a JSON object");
        return reply(res, s, b);
      }
      const auto [s, b] = h(j);
      reply(res, s, b);
    });
  }

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

}  // namespace ap::web
