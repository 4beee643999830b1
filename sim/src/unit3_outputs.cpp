// The unit3 run's outputs (docs/unit3-sim.md "Outputs"): trace.csv, waveforms.vcd and
// plots.svg, written from the board's per-tick samples. Plain text writers: the VCD and SVG of
// models/waveform speak the XY board's signals, these three files need nothing more.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "sim/unit3.hpp"

namespace ap::sim::unit3 {

namespace {

const char* const kAxisLower[kAxes] = {"x", "y", "z"};
const char* const kAxisUpper[kAxes] = {"X", "Y", "Z"};
const char* const kColour[kAxes] = {"#d62728", "#1f77b4", "#2ca02c"};

const char* source_name(unit3_board::Source s) {
  switch (s) {
    case unit3_board::Source::Idle: return "idle";
    case unit3_board::Source::Pc: return "pc";
    case unit3_board::Source::Joystick: return "joystick";
  }
  return "?";
}

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
      f << s.t_ms << ',' << kAxisLower[a] << ',' << source_name(x.source) << ',' << static_cast<unsigned>(x.entry) << ','
        << static_cast<int>(x.dir) << ',' << static_cast<unsigned>(x.mode) << ',' << x.counter << ',' << x.remaining << ','
        << static_cast<unsigned>(x.pulses) << ',' << (x.running ? 1 : 0) << ',' << x.pulse_at << '\n';
    }
  }
}

// 1 us timescale. DIR and MODE2..0 change at the start of the tick that drives them; a STEP
// pulse rises at its timer clock (4 us each) and is 2 us high, above the DRV8825's 1.9 us
// minimum (seed 001 §3.2 [EXT]).
void write_vcd(const std::vector<TickSample>& samples, const std::string& path) {
  struct Event {
    std::uint64_t t;
    char id;
    bool v;
  };
  // Identifiers: axis a's step, dir, mode0, mode1, mode2 are '!' + 5a + 0..4.
  const auto id = [](std::size_t a, std::size_t k) { return static_cast<char>('!' + 5 * a + k); };
  std::vector<Event> ev;
  std::array<std::array<bool, 5>, kAxes> level{};
  for (std::size_t a = 0; a < kAxes; ++a) level[a] = {false, true, false, false, false};
  if (!samples.empty()) {
    for (std::size_t a = 0; a < kAxes; ++a) {
      const AxisSample& x = samples.front().axis[a];
      level[a] = {false, x.dir > 0, (x.mode & 1U) != 0, (x.mode & 2U) != 0, (x.mode & 4U) != 0};
    }
  }
  const auto initial = level;
  for (const TickSample& s : samples) {
    const std::uint64_t t0 = (s.t_ms - 1) * 1000;
    for (std::size_t a = 0; a < kAxes; ++a) {
      const AxisSample& x = s.axis[a];
      const std::array<bool, 5> want{false, x.dir > 0, (x.mode & 1U) != 0, (x.mode & 2U) != 0, (x.mode & 4U) != 0};
      for (std::size_t k = 1; k < 5; ++k) {
        if (want[k] != level[a][k]) ev.push_back({t0, id(a, k), want[k]});
        level[a][k] = want[k];
      }
      if (x.pulses > 0) {
        const std::uint64_t rise = t0 + 4U * x.pulse_at;
        ev.push_back({rise, id(a, 0), true});
        ev.push_back({rise + 2, id(a, 0), false});
      }
    }
  }
  std::stable_sort(ev.begin(), ev.end(), [](const Event& l, const Event& r) { return l.t < r.t; });
  std::ofstream f = open(path);
  f << "$version axisproof sim unit3 $end\n$timescale 1us $end\n$scope module unit3 $end\n";
  static const char* const kName[5] = {"step", "dir", "mode0", "mode1", "mode2"};
  for (std::size_t a = 0; a < kAxes; ++a) {
    f << "$scope module " << kAxisUpper[a] << " $end\n";
    for (std::size_t k = 0; k < 5; ++k) f << "$var wire 1 " << id(a, k) << ' ' << kName[k] << " $end\n";
    f << "$upscope $end\n";
  }
  f << "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n";
  for (std::size_t a = 0; a < kAxes; ++a) {
    for (std::size_t k = 0; k < 5; ++k) f << (initial[a][k] ? '1' : '0') << id(a, k) << '\n';
  }
  f << "$end\n";
  std::uint64_t now = 0;
  for (const Event& e : ev) {
    if (e.t != now) {
      f << '#' << e.t << '\n';
      now = e.t;
    }
    f << (e.v ? '1' : '0') << e.id << '\n';
  }
  const std::uint64_t last = samples.empty() ? 0 : samples.back().t_ms * 1000;
  if (last > now) f << '#' << last << '\n';
}

// Two panels over the run's time: each axis's counter (1/32-step counts), and its step
// frequency with the ramp entry it stands for (entry i = 25 + 25 i Hz, core/unit3_ramp).
void write_svg(const std::vector<TickSample>& samples, const std::string& title, const std::string& path) {
  constexpr double kW = 960, kH = 640, kLeft = 90, kRight = 30, kTop = 40, kPanel = 250, kGap = 60;
  const double t_end = samples.empty() ? 1.0 : static_cast<double>(samples.back().t_ms);
  const double plot_w = kW - kLeft - kRight;
  const auto xpx = [&](double t_ms) { return kLeft + plot_w * t_ms / t_end; };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kW << "\" height=\"" << kH << "\" viewBox=\"0 0 " << kW << ' ' << kH
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"15\">unit3 " << title << "</text>\n";
  // value(sample, axis) of one panel; pixel columns keep their min and max so a long run stays small.
  const auto panel = [&](double top, const char* label, const auto& value) {
    double lo = 0, hi = 0;
    for (const TickSample& s : samples) {
      for (std::size_t a = 0; a < kAxes; ++a) {
        lo = std::min(lo, value(s.axis[a]));
        hi = std::max(hi, value(s.axis[a]));
      }
    }
    if (hi - lo < 1e-9) hi = lo + 1;
    const auto ypx = [&](double v) { return top + kPanel - kPanel * (v - lo) / (hi - lo); };
    svg << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << plot_w << "\" height=\"" << kPanel
        << "\" fill=\"none\" stroke=\"#888\"/>\n";
    svg << "<text x=\"" << kLeft << "\" y=\"" << top - 6 << "\">" << label << "</text>\n";
    for (const double v : {lo, 0.0, hi}) {
      svg << "<text x=\"" << kLeft - 6 << "\" y=\"" << ypx(v) + 4 << "\" text-anchor=\"end\">" << static_cast<long long>(v)
          << "</text>\n<line x1=\"" << kLeft << "\" x2=\"" << kLeft + plot_w << "\" y1=\"" << ypx(v) << "\" y2=\"" << ypx(v)
          << "\" stroke=\"#eee\"/>\n";
    }
    const double step_ms = t_end > 10'000 ? 5000 : t_end > 2000 ? 1000 : t_end > 500 ? 100 : 10;
    for (double t = 0; t <= t_end; t += step_ms) {
      svg << "<text x=\"" << xpx(t) << "\" y=\"" << top + kPanel + 15 << "\" text-anchor=\"middle\">" << t / 1000 << " s</text>\n";
    }
    for (std::size_t a = 0; a < kAxes; ++a) {
      svg << "<polyline fill=\"none\" stroke=\"" << kColour[a] << "\" stroke-width=\"1.2\" points=\"";
      long col = -1;
      double mn = 0, mx = 0, first = 0, last = 0;
      // A flat stretch needs only its ends: a column is written when its values differ from
      // the last one drawn, preceded by the old value at this column (the step's corner).
      std::optional<double> drawn;
      long drawn_col = -1;
      const auto flush = [&] {
        if (col < 0) return;
        for (const double v : {first, mn, mx, last}) {
          if (drawn && *drawn == v) continue;
          if (drawn && drawn_col != col) svg << col << ',' << ypx(*drawn) << ' ';
          svg << col << ',' << ypx(v) << ' ';
          drawn = v;
          drawn_col = col;
        }
      };
      for (const TickSample& s : samples) {
        const double v = value(s.axis[a]);
        const long c = static_cast<long>(xpx(static_cast<double>(s.t_ms)));
        if (c != col) {
          flush();
          col = c;
          mn = mx = first = v;
        }
        mn = std::min(mn, v);
        mx = std::max(mx, v);
        last = v;
      }
      flush();
      if (!samples.empty()) svg << col << ',' << ypx(last);
      svg << "\"/>\n";
      svg << "<text x=\"" << kLeft + plot_w - 60 + 20.0 * static_cast<double>(a) << "\" y=\"" << top - 6 << "\" fill=\"" << kColour[a]
          << "\">" << kAxisUpper[a] << "</text>\n";
    }
  };
  panel(kTop + 10, "counter (1/32-step counts)", [](const AxisSample& x) { return static_cast<double>(x.counter); });
  panel(kTop + 10 + kPanel + kGap, "step frequency, Hz (ramp entry i = 25 + 25 i Hz; 0 at rest)", [](const AxisSample& x) {
    return x.running ? static_cast<double>(unit3_ramp::entry_hz(x.entry)) : 0.0;
  });
  svg << "</svg>\n";
  std::ofstream f = open(path);
  f << svg.str();
}

}  // namespace ap::sim::unit3
