// The simulated PC of a run (docs/sim.md "The simulated PC"): the boards' PC endpoints on the
// bus, each with its delivery client and fault links; actions, expectations, the safety, delivery
// and echo checks. run_scenario() (run.cpp) hosts the boards and calls it.
#pragma once

#include <cstdint>

#include "sim/xy/scenario.hpp"
#include "sim/xy/verdict.hpp"

namespace ap::sim::xy {

RunResult run_pc(const scenario::Scenario& s, const RunOptions& opt, std::uint32_t domain);

}  // namespace ap::sim::xy
