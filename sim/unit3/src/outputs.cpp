// The unit3 run's outputs (docs/unit3-sim.md "Outputs"): trace.csv, waveforms.vcd and
// plots.svg, written from the board's per-tick samples with the VCD and SVG writers of
// models/waveform.
#include <array>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "sim/unit3/unit3.hpp"

namespace ap::sim::unit3 {

namespace {

const char* const kAxisLower[kAxes] = {"x", "y", "z"};
const char* const kAxisUpper[kAxes] = {"X", "Y", "Z"};
const char* const kColour[kAxes] = {"#d62728", "#1f77b4", "#2ca02c"};

std::ofstream open(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

}  // namespace

void write_trace_csv(const std::vector<TickSample>& samples, const std::string& path) {
  std::ofstream f = open(path);
  f << "t_ms,axis,source,entry,dir,mode,counter,remaining,pulses,running,pulse_at\n";
  for (const TickSample& s : samples) {
    for (std::size_t a = 0; a < kAxes; ++a) {
      const AxisSample& x = s.axis[a];
      f << s.t_ms << ',' << kAxisLower[a] << ',' << unit3_board::source_key(x.source) << ',' << static_cast<unsigned>(x.entry) << ','
        << static_cast<int>(x.dir) << ',' << static_cast<unsigned>(x.mode) << ',' << x.counter << ',' << x.remaining << ','
        << static_cast<unsigned>(x.pulses) << ',' << (x.running ? 1 : 0) << ',' << x.pulse_at << '\n';
    }
  }
}

// 1 us timescale, the VCD writer of models/waveform. DIR and MODE2..0 change at the start of
// the tick that drives them; a STEP pulse rises at its timer clock (4 us each) and is 2 us
// high, above the DRV8825's 1.9 us minimum (seed 001 §3.2 [EXT]).
void write_vcd(const std::vector<TickSample>& samples, const std::string& path) {
  std::ofstream f = open(path);
  namespace wf = model::waveform;
  wf::VcdWriter vcd(f, wf::VcdWriter::Options{"1us", "axisproof sim unit3", ""});
  static const char* const kName[5] = {"step", "dir", "mode0", "mode1", "mode2"};
  const auto levels = [](const AxisSample& x) {
    return std::array<std::uint64_t, 5>{0, x.dir > 0 ? 1U : 0U, x.mode & 1U, (x.mode >> 1) & 1U, (x.mode >> 2) & 1U};
  };
  std::array<std::array<int, 5>, kAxes> wire{};
  for (std::size_t a = 0; a < kAxes; ++a) {
    const auto first = samples.empty() ? std::array<std::uint64_t, 5>{0, 1, 0, 0, 0} : levels(samples.front().axis[a]);
    for (std::size_t k = 0; k < 5; ++k) wire[a][k] = vcd.wire(std::string("unit3.") + kAxisUpper[a], kName[k], 1, first[k]);
  }
  for (const TickSample& s : samples) {
    const std::uint64_t t0 = (s.t_ms - 1) * 1000;
    for (std::size_t a = 0; a < kAxes; ++a) {
      const AxisSample& x = s.axis[a];
      const auto want = levels(x);
      for (std::size_t k = 1; k < 5; ++k) vcd.set(t0, wire[a][k], want[k]);  // unchanged levels are dropped
      if (x.pulses > 0) {
        const std::uint64_t rise = t0 + 4U * x.pulse_at;
        vcd.set(rise, wire[a][0], 1);
        vcd.set(rise + 2, wire[a][0], 0);
      }
    }
  }
  vcd.finish();
}

// Two panels over the run's time (the SVG writer of models/waveform): each axis's counter
// (1/32-step counts), and its step frequency, the ramp entry it runs at (entry i = 25 + 10 i +
// i (i - 1) / 2 Hz, core/unit3/ramp and docs/unit3.md; 0 at rest).
void write_svg(const std::vector<TickSample>& samples, const std::string& title, const std::string& path) {
  namespace wf = model::waveform;
  std::array<wf::Panel, 2> panels{
      wf::Panel{"counter", "t [s]", "1/32-step counts", {}},
      wf::Panel{"step frequency", "t [s]", "Hz (ramp entry i = 25 + 10 i + i(i-1)/2 Hz)", {}},
  };
  for (std::size_t a = 0; a < kAxes; ++a) {
    wf::Series counter{kAxisUpper[a], {}, {}, kColour[a], false};
    wf::Series hz{kAxisUpper[a], {}, {}, kColour[a], false};
    for (const TickSample& s : samples) {
      const double t = static_cast<double>(s.t_ms) / 1000.0;
      const AxisSample& x = s.axis[a];
      counter.x.push_back(t);
      counter.y.push_back(static_cast<double>(x.counter));
      hz.x.push_back(t);
      hz.y.push_back(x.running ? static_cast<double>(unit3_ramp::entry_hz(x.entry)) : 0.0);
    }
    panels[0].series.push_back(std::move(counter));
    panels[1].series.push_back(std::move(hz));
  }
  std::ofstream f = open(path);
  wf::write_svg(f, "unit3 " + title, panels);
}

}  // namespace ap::sim::unit3
