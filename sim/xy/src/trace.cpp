#include "sim/xy/trace.hpp"

#include "core/xy/axis/step_timer.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace ap::sim::xy {

TraceWriter::TraceWriter(const std::string& path) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(p.parent_path(), ec);
  }
  out_.open(path, std::ios::trunc);
  if (out_) {
    out_ << kTraceHeader << '\n';
  }
}

TraceRow make_row(int64_t t_us, char axis, const ap::xy_axis::State& s, const ap::xy_axis::Input& in,
                  const ap::xy_axis::Output& out) {
  TraceRow r;
  r.t_us = t_us;
  r.axis = axis;
  r.state = ap::xy_axis::phase_name(s.phase);
  r.mode = ap::xy_axis::mode_name(s.mode);
  r.pos = s.pos;
  r.target = s.target;
  // The speed STEP pulses went out at during this tick (0 on the start tick: DIR setup).
  r.speed = out.step_speed / ap::xy_axis::kSpeedScale;
  r.dir = s.dir;
  r.endstop_min = in.endstop_min != 0 ? 1 : 0;
  r.endstop_max = in.endstop_max != 0 ? 1 : 0;
  r.blocked = in.blocked != 0 ? 1 : 0;
  r.steps = out.steps;
  r.edge = ap::xy_axis::edge_letter(out.edge);
  r.error = static_cast<int>(out.error);
  return r;
}

void TraceWriter::row(const TraceRow& r) {
  out_ << r.t_us << ',' << r.axis << ',' << r.state << ',' << r.mode << ',' << r.pos << ',' << r.target << ','
       << r.speed << ',' << r.dir << ',' << r.endstop_min << ',' << r.endstop_max << ',' << r.blocked << ','
       << r.steps << ',' << r.edge << ',' << r.error << '\n';
}

void TraceWriter::row(int64_t t_us, char axis, const ap::xy_axis::State& s, const ap::xy_axis::Input& in,
                      const ap::xy_axis::Output& out) {
  row(make_row(t_us, axis, s, in, out));
}

bool read_trace(const std::string& path, std::vector<TraceRow>& rows) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line != kTraceHeader) {
    return false;
  }
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<std::string> f;
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      f.push_back(cell);
    }
    if (f.size() != 14 || f[1].size() != 1 || f[12].size() != 1) {
      return false;
    }
    try {
      TraceRow r;
      r.t_us = std::stoll(f[0]);
      r.axis = f[1][0];
      r.state = f[2];
      r.mode = f[3];
      r.pos = std::stoll(f[4]);
      r.target = std::stoll(f[5]);
      r.speed = std::stoll(f[6]);
      r.dir = std::stoi(f[7]);
      r.endstop_min = std::stoi(f[8]);
      r.endstop_max = std::stoi(f[9]);
      r.blocked = std::stoi(f[10]);
      r.steps = std::stoll(f[11]);
      r.edge = f[12][0];
      r.error = std::stoi(f[13]);
      rows.push_back(r);
    } catch (...) {
      return false;
    }
  }
  return true;
}

}  // namespace ap::sim::xy


namespace ap::sim::xy {

namespace {
constexpr uint64_t kClkPerTick = static_cast<uint64_t>(ap::xy_axis::kTimerClockHz) / ap::xy_axis::kTicksPerSecond;
constexpr int64_t kNsPerClk_num = 25;  // 1 clock = 12.5 ns = 25/2 ns
constexpr int64_t kNsPerClk_den = 2;
}  // namespace

void StepClock::tick(int64_t t0_ns, const ap::xy_axis::Output& out, std::vector<int64_t>& edges_ns) {
  if (out.steps <= 0 || out.step_speed <= 0) {
    // Timer stopped (or no pulse): the next start begins a fresh period.
    since_edge_clk_ = out.step_speed > 0 ? since_edge_clk_ + kClkPerTick : 0;
    return;
  }
  // Rounded up, so the realised frequency is never below the core's fine speed.
  const uint32_t f_hz = static_cast<uint32_t>(
      std::max(1, (out.step_speed + ap::xy_axis::kSpeedScale - 1) / ap::xy_axis::kSpeedScale));
  const auto t = ap::xy_axis::step_timer(f_hz);
  period_ = t ? ap::xy_axis::timer_period_clocks(*t) : 2;
  // First edge one period after the previous edge (or at once if that already passed).
  uint64_t at = period_ > since_edge_clk_ ? period_ - since_edge_clk_ : 0;
  uint64_t last = 0;
  for (int32_t i = 0; i < out.steps; ++i) {
    uint64_t e = at + static_cast<uint64_t>(i) * period_;
    if (e >= kClkPerTick) {
      e = kClkPerTick - 1;
      ++squeezed_;
    }
    last = e;
    edges_ns.push_back(t0_ns + static_cast<int64_t>(e) * kNsPerClk_num / kNsPerClk_den);
  }
  since_edge_clk_ = kClkPerTick - last;
}

StepWriter::StepWriter(const std::string& path) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(p.parent_path(), ec);
  }
  out_.open(path, std::ios::trunc);
  if (out_) {
    out_ << "t_ns,axis,dir\n";
  }
}

void StepWriter::edges(char axis, int dir, const std::vector<int64_t>& edges_ns) {
  for (const int64_t e : edges_ns) {
    out_ << e << ',' << axis << ',' << dir << '\n';
  }
}

}  // namespace ap::sim::xy
