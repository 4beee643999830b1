// The run of a scenario (docs/sim.md): the boards hosted on their own threads (unless joined
// from elsewhere), the simulated PC, the verdict and its report file.
#include "sim/xy/run.hpp"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>
#include <vector>

#include "pc/dds/domain.hpp"
#include "sim/xy/board.hpp"
#include "pc.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;

RunResult run_scenario(const sc::Scenario& s, const RunOptions& opt) {
  dds::use_loopback_config(false);
  std::optional<dds::DomainLease> lease;
  const std::uint32_t domain = dds::fixed_or_claimed(opt.domain, lease);
  std::string out_dir;
  if (!opt.out_root.empty()) out_dir = opt.out_root + "/" + s.name;
  std::atomic<bool> stop{false};
  std::vector<std::thread> threads;
  std::vector<int> rc(opt.join ? 0 : s.boards, -1);
  dds::ParticipantPtr board_pp;
  if (!opt.join) {
    board_pp = dds::make_participant(domain);
    for (std::uint32_t b = 0; b < s.boards; ++b) {
      BoardOptions bo;
      bo.id = b;
      bo.baud = s.baud;
      bo.qemu_image = opt.qemu_image;
      if (b == 0) bo.out_dir = out_dir;
      threads.emplace_back([&, bo] {
        try {
          rc[bo.id] = serve_board(board_pp, bo, std::chrono::seconds(60), &stop);
        } catch (const std::exception& e) {
          rc[bo.id] = 3;
          if (opt.log != nullptr) *opt.log << "board " << bo.id << ": " << e.what() << '\n';
        }
      });
    }
  }
  RunResult r;
  try {
    r = run_pc(s, opt, domain);
  } catch (...) {
    stop = true;
    for (auto& th : threads) th.join();
    throw;
  }
  for (auto& th : threads) th.join();
  for (std::size_t b = 0; b < rc.size(); ++b) {
    if (rc[b] != 0) {
      r.failures.push_back("board " + std::to_string(b) + " did not shut down cleanly (code " + std::to_string(rc[b]) + ")");
      r.pass = false;
    }
  }
  r.domain = domain;
  r.out_dir = opt.join ? std::string() : out_dir;
  if (!out_dir.empty()) {
    std::filesystem::create_directories(out_dir);
    std::ofstream(out_dir + "/report.txt") << format_report(s, r);
  }
  return r;
}

}  // namespace ap::sim::xy
