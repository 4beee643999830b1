// The thesis's test program (seed-003.md §2.5), read from scenarios/xy/gcode/thesis.gcode.
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace gcode_test {

inline std::vector<std::string> thesis_lines() {
  std::ifstream in(std::string(AP_SOURCE_DIR) + "/scenarios/xy/gcode/thesis.gcode");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

}  // namespace gcode_test
