#pragma once
// Replays a counterexample case written by `axisproof prove` (models/smt/axis_obligations.hpp
// gives the format) through the REAL step() / step_timer() and checks the physical claims the
// obligations make. Independent of the Z3 encoding: it links only core/axis.
#include <string>
#include <vector>

#include "core/axis/axis.hpp"

namespace smt_replay {

struct Case {
  std::string file;
  std::string obligation;
  std::string kind = "motion";
  ap::axis::Config config{};
  ap::axis::State state{};
  std::vector<ap::axis::Input> inputs;
  int run = 0;
  unsigned timer_f = 0;
};

bool parse(const std::string& path, Case& out, std::string& error);
// Every violated claim, one line each ("" when the case passes).
std::string violations(const Case& c);
std::vector<std::string> case_files(const std::string& dir);

}  // namespace smt_replay
