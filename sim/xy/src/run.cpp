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
#include "sim/lockstep.hpp"
#include "sim/xy/board.hpp"
#include "pc.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;

// The shared lockstep frame (sim/lockstep.hpp) with XY's shape: the scenario's boards, each
// named by its number; board 0 writes the outputs (docs/sim.md "With several boards, only board
// 0 writes files"); a joined run writes its report too (docs/sim.md "Every run's report is also
// written to out/sim/xy/NAME/report.txt"). Realtime pacing and the fault links are the PC's.
RunResult run_scenario(const sc::Scenario& s, const RunOptions& opt) {
  return run_lockstep(
      "xy", s.name, opt, LockstepBoards{.count = s.boards, .numbered = true, .report_when_joined = true},
      [&](const dds::ParticipantPtr& pp, std::uint32_t b, const std::string& out_dir, const std::atomic<bool>* stop) {
        BoardOptions bo;
        bo.id = b;
        bo.baud = s.baud;
        bo.qemu_image = opt.qemu_image;
        if (b == 0) bo.out_dir = out_dir;
        return serve_board(pp, bo, std::chrono::seconds(60), stop);
      },
      [&](std::uint32_t domain) { return run_pc(s, opt, domain); }, [&](const RunResult& r) { return format_report(s, r); });
}

}  // namespace ap::sim::xy
