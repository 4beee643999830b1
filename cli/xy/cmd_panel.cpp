// axisproof panel --profile xy (docs/panel.md): the boards on their own threads (unless
// attached to boards already on the bus), the panel's session on the PC side of the same DDS
// domain, and the web page until Ctrl-C. The time from start to a usable page is printed.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "pc/dds/bus.hpp"
#include "pc/dds/domain.hpp"
#include "pc/web/server.hpp"
#include "pc/xy/panel/routes.hpp"
#include "pc/xy/panel/session.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/xy/board.hpp"
#include "sim/xy/fault_link.hpp"
#include "sim/xy/scenario.hpp"
#include "sim/xy/run.hpp"

namespace ap::cli {

namespace {

// The simulator's fault link in each direction, frame by frame as the simulated PC uses it
// (sim/xy/src/pc_transport.cpp), behind the panel's link filter.
class FaultFilter : public xy_panel::LinkFilter {
 public:
  FaultFilter(const std::vector<sim::xy::scenario::Fault>& faults, std::uint32_t board)
      : down_(faults, sim::xy::scenario::Direction::to_board, 1'000'003ULL + board * 2ULL),
        up_(faults, sim::xy::scenario::Direction::to_pc, 1'000'003ULL + board * 2ULL + 1ULL) {}
  std::string to_board(std::int64_t t, const std::string& bytes) override {
    if (!bytes.empty()) down_.push(t, sim::xy::Bytes(bytes.begin(), bytes.end()), stats_);
    const sim::xy::Bytes out = down_.pop(t, 3 * xy_codec::kCommandLength, stats_);
    return {out.begin(), out.end()};
  }
  std::string to_pc(std::int64_t t, const std::string& bytes) override {
    for (std::size_t k = 0; k + xy_codec::kEchoLength <= bytes.size(); k += xy_codec::kEchoLength) {
      up_.push(t, sim::xy::Bytes(bytes.begin() + static_cast<std::ptrdiff_t>(k),
                                 bytes.begin() + static_cast<std::ptrdiff_t>(k + xy_codec::kEchoLength)),
               stats_);
    }
    const sim::xy::Bytes in = up_.pop(t, 64 * xy_codec::kEchoLength, stats_);
    return {in.begin(), in.end()};
  }

 private:
  sim::xy::FaultLink down_, up_;
  sim::xy::LinkStats stats_;
};

// "drop 30 %; corrupt 10 %" as a scenario's fault lines (docs/scenarios.md), checked by its parser.
std::vector<sim::xy::scenario::Fault> parse_faults(const std::string& spec) {
  std::string text = "scenario panel\nduration 1 s\n";
  std::size_t from = 0;
  while (from <= spec.size()) {
    const std::size_t end = spec.find(';', from);
    const std::string item = spec.substr(from, end == std::string::npos ? std::string::npos : end - from);
    if (item.find_first_not_of(" \t") != std::string::npos) text += "fault " + item + "\n";
    if (end == std::string::npos) break;
    from = end + 1;
  }
  return sim::xy::scenario::parse(text, "--faults").faults;
}

}  // namespace

int xy_panel(const PanelArgs& a) {
  const auto started = std::chrono::steady_clock::now();
  try {
    if (a.target != "host" && a.target != "qemu") throw std::runtime_error("--target " + a.target + ": host or qemu");
    if (a.attach && a.target != "host") throw std::runtime_error("--attach uses boards that run elsewhere: no --target");
    dds::use_loopback_config(false);
    std::optional<dds::DomainLease> lease;
    const std::uint32_t domain =
        dds::fixed_or_claimed(a.domain >= 0 ? std::optional<std::uint32_t>(static_cast<std::uint32_t>(a.domain)) : std::nullopt, lease);
    const std::string image = a.target == "qemu" ? xy_qemu_image() : std::string();

    std::atomic<bool> stop{false};
    std::vector<std::thread> boards;
    dds::ParticipantPtr pp;
    if (!a.attach) {
      pp = dds::make_participant(domain);
      for (std::uint32_t b = 0; b < a.boards; ++b) {
        boards.emplace_back([&, b] {
          try {
            sim::xy::BoardOptions o;
            o.id = b;
            o.qemu_image = image;
            (void)sim::xy::serve_board(pp, o, std::chrono::hours(24), &stop);
          } catch (const std::exception& e) {
            std::fprintf(stderr, "axisproof panel: board %u: %s\n", b, e.what());
          }
        });
      }
    }
    xy_panel::Options so;
    so.domain = domain;
    if (!a.faults.empty()) {
      const auto faults = parse_faults(a.faults);
      so.link = [faults](std::uint32_t board) { return std::make_unique<FaultFilter>(faults, board); };
    }
    so.boards.clear();
    for (std::uint32_t b = 0; b < a.boards; ++b) so.boards.push_back(b);
    int rc = 0;
    {
      xy_panel::Session session(so);
      const bool ok = web::serve(
          xy_panel::routes(session, "axisproof panel: XY platform (seed 000)"), xy_panel::web_options(a.port),
          [&](int port) {
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            std::printf("axisproof panel: http://127.0.0.1:%d/ (profile xy, %u board(s) %s on DDS domain %u%s; ready in %.2f s; Ctrl-C ends)\n",
                        port, a.boards, a.attach ? "attached" : (a.target == "qemu" ? "in QEMU" : "in-process"), domain,
                        a.faults.empty() ? "" : ", faults on the link", s);
            std::fflush(stdout);
          },
          [] { return panel_stop_requested(); });
      if (!ok) {
        std::fprintf(stderr, "axisproof panel: cannot listen on 127.0.0.1:%d\n", a.port);
        rc = 1;
      }
      session.stop();
    }
    stop = true;
    for (auto& t : boards) t.join();
    return rc;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof panel: %s\n", e.what());
    return 1;
  }
}

}  // namespace ap::cli
