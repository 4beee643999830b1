// The simulated PC's run (docs/sim.md "The simulated PC"): the order of things in a lockstep
// step and at the end of a run, which decides the order of the report's failures. What each
// step does is in the files of its own job: pc_actions (the scenario's actions), pc_transport
// (the client over the links and the bus), pc_delivery, pc_echoes and pc_safety (the checks),
// pc_expectations, report.cpp (the verdict's figures).
#include "pc.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "pc_actions.hpp"
#include "pc_board.hpp"
#include "pc_expectations.hpp"
#include "pc_transport.hpp"
#include "report.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;

namespace {

class Pc {
 public:
  Pc(const sc::Scenario& s, const RunOptions& opt, std::uint32_t domain) : pc_(s, opt), expect_(pc_) {
    pp_ = dds::make_participant(domain);
    for (std::uint32_t b = 0; b < s.boards; ++b) boards_.push_back(std::make_unique<BoardPc>(pc_, pp_, b));
    pc_.mech = assumed_mechanics(s);
    pc_.param_slots = expected_params(s);
  }

  ~Pc() {
    boards_.clear();
    pp_.reset();
  }

  Pc(const Pc&) = delete;
  Pc& operator=(const Pc&) = delete;

  RunResult run() {
    const sc::Scenario& s = pc_.s;
    const RunOptions& opt = pc_.opt;
    const auto wall0 = std::chrono::steady_clock::now();
    connect(boards_);
    set_up(pc_, boards_);
    std::size_t next_action = 0;
    std::int64_t t = 0;
    for (; t <= s.duration_us; t += opt.step_us) {
      if (opt.realtime) std::this_thread::sleep_until(wall0 + std::chrono::microseconds(t));
      while (next_action < s.actions.size() && s.actions[next_action].t_us <= t) {
        apply(pc_, boards_, s.actions[next_action], t);
        ++next_action;
      }
      step(pc_, boards_, t);
      for (auto& b : boards_) {
        b->safety.check(pc_, *b, t);
        expect_.evaluate(*b, t, false);
      }
    }
    t -= opt.step_us;
    for (auto& b : boards_) expect_.evaluate(*b, t, true);
    finish(t);
    RunResult r;
    r.failures = pc_.failures;
    r.pass = pc_.failures.empty();
    r.vtime_us = t;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    r.bus_round_trips = pc_.round_trips;
    r.domain = pp_->domain();
    for (auto& b : boards_) r.boards.push_back(b->verdict);
    return r;
  }

 private:
  void finish(std::int64_t t) {
    for (auto& bp : boards_) {
      BoardPc& b = *bp;
      const std::string viol = env(pc_, b, "probe violations", t);
      if (!viol.empty() && viol[0] != '0') pc_.fail("safety (board-side monitor, every tick): board " + std::to_string(b.id) + ": " + viol);
      b.verdict.lost_step_risks = static_cast<std::uint64_t>(std::stoull(env(pc_, b, "probe lost_steps", t)));
      b.echoes.finish(b, t);
      report_client(b.verdict, b.client->counters(), b.delivery.frames_answered(), b.delivery.reports());
      b.delivery.finish(pc_, b, t);
    }
    shut_down(boards_, t);
  }

  PcContext pc_;
  dds::ParticipantPtr pp_;
  Boards boards_;
  Expectations expect_;
};

}  // namespace

RunResult run_pc(const sc::Scenario& s, const RunOptions& opt, std::uint32_t domain) {
  Pc pc(s, opt, domain);
  return pc.run();
}

}  // namespace ap::sim::xy
