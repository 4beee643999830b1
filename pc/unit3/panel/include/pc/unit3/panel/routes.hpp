// The unit3 panel's API on the shared web server (pc/web, docs/panel.md "The unit3 panel").
#pragma once

#include <string>

#include "pc/web/server.hpp"
#include "pc/unit3/panel/session.hpp"

namespace ap::unit3_panel {

web::Routes routes(Session& s, const std::string& title);
web::Options web_options(int port);

}  // namespace ap::unit3_panel
