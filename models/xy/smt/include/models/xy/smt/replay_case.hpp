#pragma once
// The replay case of a counterexample (one format, its writer and its reader): `axisproof prove`
// writes one per FAILED obligation (out/prove/<obligation>.case), properties/xy/smt replays it
// through the real step() / step_timer(). Kept apart from the Z3 encodings (library
// ap_xy_smt_case links only core/xy/axis), so the replay stays independent of them.
//
// Text, one item per line: `obligation NAME`, `kind motion|timer|table|watchdog`, `timer F`,
// `config v_start v_slow v_fast accel soft_min soft_max home_travel home_position`,
// `state phase mode dir jog_dir level latch_min latch_max homed pos target v frac`,
// `input kind dir level value endstop_min endstop_max blocked link_alive` (one per tick),
// `run N`; `#` starts a comment line.
#include <string>
#include <vector>

#include "core/xy/axis/axis.hpp"

namespace ap::model::smt {

struct ReplayCase {
  std::string obligation;
  std::string kind = "motion";
  ap::xy_axis::Config config{};
  ap::xy_axis::State state{};
  std::vector<ap::xy_axis::Input> inputs;
  int run = 0;
  unsigned timer_f = 0;
};

std::string format_case(const ReplayCase& c);
// Writes out/prove/<obligation>.case (directory from $AP_PROVE_OUT if set); returns the path.
std::string write_case(const ReplayCase& c);
// Reads a case file; false with `error` set on an unreadable file or a bad line.
bool read_case(const std::string& path, ReplayCase& out, std::string& error);

}  // namespace ap::model::smt
