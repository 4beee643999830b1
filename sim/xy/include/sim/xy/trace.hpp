// trace.csv: one row per axis per control tick. Columns (fixed order):
//   t_us,axis,state,mode,pos,target,speed,dir,endstop_min,endstop_max,blocked,steps,edge,error
// pos/target in usteps (state after the tick), speed = the speed the tick's STEP pulses were
// emitted at in usteps/s (a magnitude, floor of the fine speed), dir +1/-1 (the DIR pin), steps = STEP pulses emitted in the tick, edge = Tab. 7-3 letter taken.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "core/xy/axis/axis.hpp"

namespace ap::sim::xy {

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
  void row(int64_t t_us, char axis, const ap::xy_axis::State& s, const ap::xy_axis::Input& in,
           const ap::xy_axis::Output& out);
  void row(const TraceRow& r);

 private:
  std::ofstream out_;
};

[[nodiscard]] TraceRow make_row(int64_t t_us, char axis, const ap::xy_axis::State& s, const ap::xy_axis::Input& in,
                                const ap::xy_axis::Output& out);

// Reads a trace back; returns false on a malformed header or row.
[[nodiscard]] bool read_trace(const std::string& path, std::vector<TraceRow>& rows);

}  // namespace ap::sim::xy

namespace ap::sim::xy {

// STEP edge times as the quantised timer produces them (docs/motion.md). The core decides how
// many pulses go out in a tick; the timer, programmed by step_timer() for the tick's speed,
// spaces them (PSC+1)(ARR+1) clocks of 80 MHz apart, continuing from the previous edge. If the
// core asks for more pulses than fit before the tick ends (it can be ahead by one pulse: the
// realised frequency rounds up, the accumulator does not), the surplus goes out at the tick end
// and `squeezed` counts it.
class StepClock {
 public:
  // t0_ns: start of the tick. Appends the edge times (ns) of out.steps pulses to `edges_ns`.
  void tick(int64_t t0_ns, const ap::xy_axis::Output& out, std::vector<int64_t>& edges_ns);
  [[nodiscard]] int64_t squeezed() const { return squeezed_; }

 private:
  uint64_t since_edge_clk_ = 0;  // timer clocks from the last edge to the start of this tick
  uint64_t period_ = 0;
  int64_t squeezed_ = 0;
};

// steps.csv: one row per STEP edge: t_ns,axis,dir
class StepWriter {
 public:
  explicit StepWriter(const std::string& path);
  [[nodiscard]] bool ok() const { return static_cast<bool>(out_); }
  void edges(char axis, int dir, const std::vector<int64_t>& edges_ns);

 private:
  std::ofstream out_;
};

}  // namespace ap::sim::xy
