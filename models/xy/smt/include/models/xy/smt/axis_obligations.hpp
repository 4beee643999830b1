#pragma once
// Counterexample output shared by the axis, timer and storage obligations: a failing
// obligation prints a tick-by-tick trace and writes a replayable case file
// (models/xy/smt/replay_case.hpp: the format, its writer and its reader) that
// properties/xy/smt/smt_replay_test.cpp runs through the real step() / step_timer().
#include <string>
#include <vector>

#include "core/xy/axis/axis.hpp"
#include "models/xy/smt/replay_case.hpp"

namespace ap::model::smt {

// One line per tick: inputs, state (phase, mode, dir, pos, target, speed, frac), outputs.
// The states, inputs and outputs come from the solver's model of the encoding.
std::string format_trace(const ap::xy_axis::Config& c, const std::vector<ap::xy_axis::State>& states,
                         const std::vector<ap::xy_axis::Input>& inputs, const std::vector<ap::xy_axis::Output>& outs);

}  // namespace ap::model::smt
