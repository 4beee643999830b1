#pragma once
// Counterexample output shared by the axis, timer and storage obligations: a failing
// obligation prints a tick-by-tick trace and writes a replayable case file that
// properties/smt/smt_replay_test.cpp runs through the real step() / step_timer().
//
// Case file format (text, one item per line, '#' starts a comment):
//   obligation <name>
//   kind motion | timer | table | watchdog   (table, watchdog: no more lines; the replay checks
//                                              the whole C++ function)
//   config <v_start> <v_slow> <v_fast> <accel> <soft_min> <soft_max> <home_travel> <home_position>
//   state <phase> <mode> <dir> <jog_dir> <level> <latch_min> <latch_max> <homed> <pos> <target> <v> <frac>
//   input <kind> <dir> <level> <value> <endstop_min> <endstop_max> <blocked> <link_alive>   (one per tick)
//   run <ticks>        after the inputs, step with an empty input this many more ticks
//   timer <f_hz>       (kind timer)
#include <string>
#include <vector>

#include "core/axis/axis.hpp"

namespace ap::smt {

struct ReplayCase {
  std::string obligation;
  std::string kind = "motion";
  ap::axis::Config config{};
  ap::axis::State state{};
  std::vector<ap::axis::Input> inputs;
  int run = 0;
  unsigned timer_f = 0;
};

std::string format_case(const ReplayCase& c);
// Writes out/prove/<obligation>.case (directory from $AP_PROVE_OUT if set); returns the path.
std::string write_case(const ReplayCase& c);
// One line per tick: inputs, state (phase, mode, dir, pos, target, speed, frac), outputs.
// The states, inputs and outputs come from the solver's model of the encoding.
std::string format_trace(const ap::axis::Config& c, const std::vector<ap::axis::State>& states,
                         const std::vector<ap::axis::Input>& inputs, const std::vector<ap::axis::Output>& outs);

}  // namespace ap::smt
