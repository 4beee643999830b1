// axisproof panel --profile unit3 (docs/panel.md "The unit3 panel"): seed 001's PC program on
// one simulated unit; panel_main does the rest.
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "cli.hpp"
#include "commands.hpp"
#include "pc/unit3/panel/routes.hpp"
#include "pc/unit3/panel/session.hpp"
#include "pc/web/server.hpp"
#include "sim/unit3/unit3.hpp"

namespace ap::cli {

int unit3_panel(const PanelArgs& a) {
  try {
    if (a.target != "host") throw std::runtime_error("--target " + a.target + ": this profile has no image (docs/profiles.md)");
    // The seed's program drives one unit over one serial port (seed-001.md §7).
    if (a.boards != 1) throw std::runtime_error("--boards: the unit3 program drives one unit");
    if (!a.faults.empty()) throw std::runtime_error("--faults: the unit3 link has no fault injector yet (docs/panel.md)");
    return panel_main(
        a, "unit3",
        [](const dds::ParticipantPtr& pp, std::uint32_t id, const std::atomic<bool>* stop) {
          sim::unit3::BoardOptions o;
          o.id = id;
          (void)sim::unit3::serve_board(pp, o, std::chrono::hours(24), stop);
        },
        [&](std::uint32_t domain, const std::function<void(int)>& ready) {
          unit3_panel::Options so;
          so.domain = domain;
          unit3_panel::Session session(so);
          const bool ok = web::serve(unit3_panel::routes(session, "axisproof panel: 3-axis unit (seed 001)"),
                                     unit3_panel::web_options(a.port), ready, [] { return panel_stop_requested(); });
          session.stop();
          return ok;
        });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof panel: %s\n", e.what());
    return 1;
  }
}

}  // namespace ap::cli
