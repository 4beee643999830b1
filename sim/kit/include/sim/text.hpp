// Number and time formatting shared by the simulated PC's messages and the report.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>

namespace ap::sim {

inline std::string fmt(double v) {
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}

inline std::string tstr(std::int64_t us) { return fmt(static_cast<double>(us) / 1e6) + " s"; }

}  // namespace ap::sim
