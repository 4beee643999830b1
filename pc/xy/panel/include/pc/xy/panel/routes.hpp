// The XY panel's API on the shared web server (pc/web, docs/panel.md "HTTP"): each route checks
// its fields' types, ranges and lengths and hands the request to the session.
#pragma once

#include <string>

#include "pc/web/server.hpp"
#include "pc/xy/panel/session.hpp"

namespace ap::xy_panel {

web::Routes routes(Session& s, const std::string& title);

// The page's files in the build (index.html, panel.js, panel.css) and their types.
web::Options web_options(int port);

}  // namespace ap::xy_panel
