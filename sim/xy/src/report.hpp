// What the report (report.cpp, docs/sim.md "Delivery check") shows of a board's client: its
// counters and settled commands, copied into the verdict at the end of a run. Not in run.hpp:
// only the simulated PC fills it.
#pragma once

#include <cstdint>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "sim/xy/verdict.hpp"

namespace ap::sim::xy {

void report_client(BoardVerdict& v, const xy_client::ClientCounters& c, std::uint64_t frames_answered,
                   const std::vector<xy_client::Report>& reports);

}  // namespace ap::sim::xy
