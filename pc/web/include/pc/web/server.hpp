// The operator panels' web server (docs/panel.md "HTTP"), the same for every profile: the page
// and its assets from a folder of the build, GET /api/info (what the profile hands out),
// GET /api/state and the server-sent events stream /api/events (the profile's snapshot every
// 100 ms with the events since the last message), and POST /api/<name> routes whose JSON body
// (at most 1 KiB, an object) the profile's handler checks with the field helpers below, so a bad
// value is answered 400 with its reason and never reaches the board. Localhost only.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace ap::web {

using json = nlohmann::json;

// A POST route: the request's JSON object in, the status (200 or 400) and the reply out.
using Handler = std::function<std::pair<int, json>(const json& body)>;

struct Routes {
  json info;                                          // GET /api/info
  std::function<json(std::uint64_t after)> snapshot;  // the state and the events with an id above `after`
  std::map<std::string, Handler> posts;               // POST /api/<key>
};

struct Options {
  std::string host = "127.0.0.1";
  int port = 8080;          // 0: any free port
  std::string assets_dir;   // index.html and the files below
  std::vector<std::pair<std::string, std::string>> assets;  // file name, content type
};

// Serves until `stopped()` is true (polled every 200 ms); `ready(port)` once the socket
// listens. False when the port cannot be bound.
bool serve(const Routes& r, const Options& o, const std::function<void(int port)>& ready,
           const std::function<bool()>& stopped);

// Field checks for the handlers: the value, else nothing and `why` says what is wrong.
std::optional<std::int64_t> int_field(const json& j, const char* name, std::int64_t lo, std::int64_t hi, std::string& why);
std::optional<std::string> str_field(const json& j, const char* name, std::size_t max_len, std::string& why);
std::optional<bool> bool_field(const json& j, const char* name, std::string& why);
// The 400 reply of a refused request.
std::pair<int, json> refused(const std::string& why);

}  // namespace ap::web
