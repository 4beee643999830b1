// The panel's web side (docs/panel.md "HTTP"): the page and its assets from the build, a JSON
// API whose every request is checked before it reaches the session, and a server-sent events
// stream of the session's state and events. Localhost only.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "pc/xy/panel/session.hpp"

namespace ap::xy_panel {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;             // 0: any free port
  std::string assets_dir;      // index.html, panel.js, panel.css
  std::string title = "axisproof panel";
  std::string profile = "xy";
};

// Serves until `stopped()` returns true (polled every 200 ms). `ready(port)` is called once
// the socket listens. Returns false when the port cannot be bound.
bool serve(Session& s, const ServerOptions& o, const std::function<void(int port)>& ready,
           const std::function<bool()>& stopped);

}  // namespace ap::xy_panel
