// The hc08 run's outputs (docs/hc08-sim.md "Outputs"): trace.csv, waveforms.vcd and plots.svg,
// written from the board's rows with the VCD and SVG writers of models/waveform.
#include <array>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "sim/hc08/hc08.hpp"

namespace ap::sim::hc08 {

namespace {

std::ofstream open(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

// t in microseconds with three decimals (to the ns; the exact unit is 1/1536 us).
std::string us_text(std::int64_t units) {
  const std::uint64_t ns = ns_of(units);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%llu.%03llu", static_cast<unsigned long long>(ns / 1000U),
                static_cast<unsigned long long>(ns % 1000U));
  return buf;
}

}  // namespace

void write_trace_csv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream f = open(path);
  f << "t_us,event,key,port,pattern,dir,period_ticks,angle_tenths,position_half,steps,running,state,indicator,value,point,error,adjusted\n";
  for (const Row& r : rows) {
    f << us_text(r.t) << ',' << event_name(r.event) << ',' << format_value(Quantity::Port, r.scan) << ','
      << format_value(Quantity::Port, r.port) << ',' << format_value(Quantity::Coils, r.coils) << ',' << static_cast<int>(r.dir)
      << ',' << r.period_ticks << ',' << value_of(r, Quantity::Angle) << ',' << r.position << ',' << r.steps << ','
      << (r.running ? 1 : 0) << ',' << menu_name(r.menu) << ',' << static_cast<unsigned>(r.display.indicator) << ','
      << r.display.value << ',' << static_cast<unsigned>(r.display.point) << ',' << (r.display.error ? 1 : 0) << ','
      << (r.display.adjusted ? 1 : 0) << '\n';
  }
}

// 1 ns timescale, the VCD writer of models/waveform. Scope hc08: phase1..phase4 are PTA3..PTA6
// (phase k on PTA(k+2) [T Tab. 4.1]), 1 = the coil energised; key is the 8-bit code the keypad
// scan reads (0: no key), changing at the scan that reads it.
void write_vcd(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream f = open(path);
  namespace wf = model::waveform;
  wf::VcdWriter vcd(f, wf::VcdWriter::Options{"1ns", "axisproof sim hc08", "phase1..4 = PTA3..PTA6; key = the keypad scan code"});
  const std::uint8_t port0 = rows.empty() ? 0 : rows.front().port;
  std::array<int, 4> phase{};
  for (unsigned k = 0; k < 4; ++k) {
    phase[k] = vcd.wire("hc08", "phase" + std::to_string(k + 1), 1, (port0 >> (3U + k)) & 1U);
  }
  const int key = vcd.wire("hc08", "key", 8, rows.empty() ? 0 : rows.front().scan);
  for (const Row& r : rows) {
    const std::uint64_t t = ns_of(r.t);
    for (unsigned k = 0; k < 4; ++k) vcd.set(t, phase[k], (r.port >> (3U + k)) & 1U);  // unchanged levels are dropped
    vcd.set(t, key, r.scan);
  }
  vcd.finish();
}

// Two panels over the run's time (the SVG writer of models/waveform): the rotor's position in
// degrees (from the coils, right +), and the step frequency of each step (0 at rest).
void write_svg(const std::vector<Row>& rows, const std::string& title, const std::string& path) {
  namespace wf = model::waveform;
  wf::Series pos{"rotor", {}, {}, "#1f77b4", false};
  wf::Series hz{"steps", {}, {}, "#d62728", false};
  bool running = false;
  for (const Row& r : rows) {
    const double t = static_cast<double>(r.t) / static_cast<double>(kUnitsPerSecond);
    pos.x.push_back(t);
    pos.y.push_back(static_cast<double>(r.position) * 4.5);
    // 0 at power-up and at rest: a start rises from 0, a motion's last step drops back to it.
    if (r.event == Event::Init || (r.running && !running)) {
      hz.x.push_back(t);
      hz.y.push_back(0.0);
    }
    if (r.event == Event::Step) {
      hz.x.push_back(t);
      hz.y.push_back(static_cast<double>(value_of(r, Quantity::Frequency)));
      if (!r.running) {
        hz.x.push_back(t);
        hz.y.push_back(0.0);
      }
    }
    running = r.running;
  }
  std::array<wf::Panel, 2> panels{
      wf::Panel{"rotor position", "t [s]", "degrees (right +)", {std::move(pos)}},
      wf::Panel{"step frequency", "t [s]", "Hz", {std::move(hz)}},
  };
  std::ofstream f = open(path);
  wf::write_svg(f, "hc08 " + title, panels);
}

}  // namespace ap::sim::hc08
