// trace.csv: one row per axis per control tick. Columns (fixed order):
//   t_us,axis,state,mode,pos,target,speed,dir,endstop_min,endstop_max,blocked,steps,edge,error
// pos/target in usteps (state after the tick), speed = the speed the tick's STEP pulses were
// emitted at in usteps/s (a magnitude, floor of the fine speed), dir +1/-1 (the DIR pin), steps = STEP pulses emitted in the tick, edge = Tab. 7-3 letter taken.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "core/axis/axis.hpp"

namespace ap::sim {

struct TraceRow {
  int64_t t_us = 0;
  char axis = 'X';
  std::string state;
  std::string mode;
  int64_t pos = 0;
  int64_t target = 0;
  int64_t speed = 0;
  int dir = 1;
  int endstop_min = 0;
  int endstop_max = 0;
  int blocked = 0;
  int64_t steps = 0;
  char edge = 'I';
  int error = 0;
};

inline constexpr const char* kTraceHeader =
    "t_us,axis,state,mode,pos,target,speed,dir,endstop_min,endstop_max,blocked,steps,edge,error";

class TraceWriter {
 public:
  // Creates the parent directories. ok() is false if the file could not be opened.
  explicit TraceWriter(const std::string& path);
  [[nodiscard]] bool ok() const { return static_cast<bool>(out_); }
  // The state after the tick, the input of the tick, and its output.
  void row(int64_t t_us, char axis, const ap::axis::State& s, const ap::axis::Input& in,
           const ap::axis::Output& out);
  void row(const TraceRow& r);

 private:
  std::ofstream out_;
};

[[nodiscard]] TraceRow make_row(int64_t t_us, char axis, const ap::axis::State& s, const ap::axis::Input& in,
                                const ap::axis::Output& out);

// Reads a trace back; returns false on a malformed header or row.
[[nodiscard]] bool read_trace(const std::string& path, std::vector<TraceRow>& rows);

}  // namespace ap::sim
