// axisproof panel: the operator's web panel of a profile (docs/panel.md). This file reads the
// arguments, turns Ctrl-C into an orderly stop and, in panel_main, does what every profile's
// panel does alike: the domain, the boards' threads (unless attached), the ready line; the
// profile's adapter brings its board server, its session and its routes.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <optional>
#include <thread>
#include <vector>

#include "pc/dds/domain.hpp"

#include "cli.hpp"
#include "profile.hpp"

namespace ap::cli {

namespace {
volatile std::sig_atomic_t g_panel_stop = 0;
void on_signal(int) { g_panel_stop = 1; }
}  // namespace

bool panel_stop_requested() { return g_panel_stop != 0; }

int panel_main(const PanelArgs& a, std::string_view label, const PanelBoard& board, const PanelServe& serve) {
  const auto started = std::chrono::steady_clock::now();
  try {
    dds::use_loopback_config(false);
    std::optional<dds::DomainLease> lease;
    const std::uint32_t domain =
        dds::fixed_or_claimed(a.domain >= 0 ? std::optional<std::uint32_t>(static_cast<std::uint32_t>(a.domain)) : std::nullopt, lease);
    std::atomic<bool> stop{false};
    std::vector<std::thread> boards;
    dds::ParticipantPtr pp;
    if (!a.attach) {
      pp = dds::make_participant(domain);
      for (std::uint32_t b = 0; b < a.boards; ++b) {
        boards.emplace_back([&, b] {
          try {
            board(pp, b, &stop);
          } catch (const std::exception& e) {
            std::fprintf(stderr, "axisproof panel: board %u: %s\n", b, e.what());
          }
        });
      }
    }
    const bool ok = serve(domain, [&](int port) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      std::printf("axisproof panel: http://127.0.0.1:%d/ (profile %.*s, %u board(s) %s on DDS domain %u%s; ready in %.2f s; Ctrl-C ends)\n",
                  port, static_cast<int>(label.size()), label.data(), a.boards,
                  a.attach ? "attached" : (a.target == "qemu" ? "in QEMU" : "in-process"), domain,
                  a.faults.empty() ? "" : ", faults on the link", s);
      std::fflush(stdout);
    });
    if (!ok) std::fprintf(stderr, "axisproof panel: cannot listen on 127.0.0.1:%d\n", a.port);
    stop = true;
    for (auto& t : boards) t.join();
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof panel: %s\n", e.what());
    return 1;
  }
}

void add_panel(CLI::App& app) {
  auto* sub = app.add_subcommand("panel", "Serve the operator's web panel on localhost, driving simulated boards");
  static PanelArgs a;
  static std::string profile;
  sub->add_option("--target", a.target, "host (the core in-process) or qemu (the profile's image)")->default_val("host");
  sub->add_option("--boards", a.boards, "Boards to start (ids 0..N-1)")->default_val(1)->check(CLI::Range(1, 16));
  sub->add_option("--port", a.port, "HTTP port on 127.0.0.1 (0: any free one)")->default_val(8080)->check(CLI::Range(0, 65535));
  sub->add_option("--domain", a.domain, "DDS domain (default: a free one; with --attach: the boards' domain)");
  sub->add_option("--faults", a.faults,
                  "A link storm under the panel: scenario fault lines joined by ';', e.g. 'drop 30 %; corrupt 10 %' (docs/scenarios.md)");
  sub->add_flag("--attach", a.attach, "Use boards already on the bus (e.g. `axisproof sim board --domain D`)");
  add_profile_option(sub, profile);
  sub->final_callback([] {
    const Profile* p = find_profile(profile);
    if (p->panel == nullptr) {
      std::fprintf(stderr, "axisproof panel: profile %s has no panel yet (docs/panel.md)\n", profile.c_str());
      exit_status() = 2;
      return;
    }
    if (a.attach && a.domain < 0) {
      std::fprintf(stderr, "axisproof panel: --attach needs --domain\n");
      exit_status() = 2;
      return;
    }
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    exit_status() = p->panel(a);
  });
}

}  // namespace ap::cli
