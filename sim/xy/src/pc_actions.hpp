// The scenario's actions as the simulated PC carries them out (docs/scenarios.md, docs/sim.md
// "The simulated PC"): user commands go to the delivery client, raw frames and link cuts to the
// fault links, physical events to the board as environment commands. Only here does the PC read
// a scenario's verbs; what it then sends is pc_transport's, what it checks the checks'.
#pragma once

#include <cstdint>

#include "sim/xy/scenario.hpp"
#include "pc_board.hpp"

namespace ap::sim::xy {

// The mechanics the PC assumes before any action: the parameter defaults and the scenario's
// `board param` / `board fram` lines.
PcMech assumed_mechanics(const scenario::Scenario& s);

// Every board's setup lines (before boot), then boot.
void set_up(PcContext& pc, Boards& boards);

// One action at t, on each board it targets.
void apply(PcContext& pc, Boards& boards, const scenario::Action& a, std::int64_t t);

}  // namespace ap::sim::xy
