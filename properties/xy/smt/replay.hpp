#pragma once
// Replays a counterexample case written by `axisproof prove` (models/xy/smt/replay_case.hpp: the
// format, its writer and its reader) through the REAL step() / step_timer() and checks the
// physical claims the obligations make. Independent of the Z3 encoding: it links only core/xy/axis
// and the case format (ap_xy_smt_case).
#include <string>
#include <vector>

#include "core/xy/axis/axis.hpp"
#include "models/xy/smt/replay_case.hpp"

namespace smt_replay {

// The case format and its reader are models/xy/smt/replay_case.hpp (next to the writer).
using Case = ap::model::smt::ReplayCase;
// Every violated claim, one line each ("" when the case passes).
std::string violations(const Case& c);
std::vector<std::string> case_files(const std::string& dir);

}  // namespace smt_replay
