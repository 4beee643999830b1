// axisproof panel --profile xy (docs/panel.md): its boards (in-process or the QEMU image), the
// link storm of --faults, the panel's session and routes; panel_main does the rest.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "pc/dds/bus.hpp"
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
  if (spec.empty()) return {};
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
  try {
    if (a.target != "host" && a.target != "qemu") throw std::runtime_error("--target " + a.target + ": host or qemu");
    if (a.attach && a.target != "host") throw std::runtime_error("--attach uses boards that run elsewhere: no --target");
    const std::string image = a.target == "qemu" ? xy_qemu_image() : std::string();
    const auto faults = parse_faults(a.faults);
    return panel_main(
        a, "xy",
        [&](const dds::ParticipantPtr& pp, std::uint32_t id, const std::atomic<bool>* stop) {
          sim::xy::BoardOptions o;
          o.id = id;
          o.qemu_image = image;
          (void)sim::xy::serve_board(pp, o, std::chrono::hours(24), stop);
        },
        [&](std::uint32_t domain, const std::function<void(int)>& ready) {
          xy_panel::Options so;
          so.domain = domain;
          so.boards.clear();
          for (std::uint32_t b = 0; b < a.boards; ++b) so.boards.push_back(b);
          if (!faults.empty()) {
            so.link = [faults](std::uint32_t board) { return std::make_unique<FaultFilter>(faults, board); };
          }
          xy_panel::Session session(so);
          const bool ok = web::serve(xy_panel::routes(session, "axisproof panel: XY platform (seed 000)"),
                                     xy_panel::web_options(a.port), ready, [] { return panel_stop_requested(); });
          session.stop();
          return ok;
        });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof panel: %s\n", e.what());
    return 1;
  }
}

}  // namespace ap::cli
