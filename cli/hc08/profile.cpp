// The HC08 single-motor unit (seed 002) as a profile (docs/profiles.md, docs/hc08.md). It has no
// link to a PC (its only input is the keypad), so it brings no wire codec: `frame` says so. Its
// end-to-end runs drive the keys over the bus and read the coil lines.
#include <iostream>
#include <stdexcept>
#include <string>

#include "cli.hpp"
#include "models/hc08/obligations.hpp"
#include "profile.hpp"
#include "sim/hc08/hc08.hpp"

namespace ap::cli {

// Named so that the three profiles' helpers stay apart in the unity build (cli/CMakeLists.txt).
namespace profile_hc08 {
namespace {

// axisproof sim board --profile hc08: boards for `sim run --profile hc08 --join --domain N`
// (docs/hc08-sim.md). Each is the unit at power-up; the keys reach it over the bus.
int sim_board(const SimBoardArgs& a) {
  return host_boards(a, "hc08", [](const dds::ParticipantPtr& pp, std::uint32_t id, const std::string& out, std::chrono::seconds idle) {
    ap::sim::hc08::BoardOptions o;
    o.id = id;
    o.out_dir = out;
    return ap::sim::hc08::serve_board(pp, o, idle);
  });
}

// axisproof sim run --profile hc08 scenarios/hc08/NAME.scn: exit 0 pass, 1 fail, 2 error.
int sim_run(const SimRunArgs& a) {
  namespace h = ap::sim::hc08;
  return sim_run_main([&]() -> SimRunVerdict {
    const h::Scenario s = h::parse_file(a.scenario);
    if (a.realtime) throw std::runtime_error("--realtime: the hc08 run has no realtime mode");
    h::RunOptions o;
    set_run_options(a, o);
    o.out_root = a.out_root;
    if (o.step_us <= 0) throw std::runtime_error("--step-ms must be positive");
    const h::RunResult r = h::run_scenario(s, o);
    std::cout << h::format_report(s, r);
    return {r.pass, r.out_dir};
  });
}

}  // namespace
}  // namespace profile_hc08

// Its adapters; the declaration (profiles/hc08.cmake) fills in the rest of its entry.
Profile ap_profile_hc08() {
  // No wire protocol (the unit has no PC link), no bootable image yet (docs/hc08.md "MCU").
  Profile p;
  p.sim_run = &profile_hc08::sim_run;
  p.sim_board = &profile_hc08::sim_board;
  p.obligations = &model::smt::hc08_obligations;
  p.registry_tests = "^Hc08Proofs\\.EveryObligationIsProved$";
  return p;
}

}  // namespace ap::cli
