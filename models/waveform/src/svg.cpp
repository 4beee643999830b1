// SVG plots (see svg.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <stdexcept>

#include "models/waveform/svg.hpp"

namespace ap::model::waveform {
namespace {

constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#17becf"};

std::string esc(std::string_view s) {
  std::string o;
  for (const char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string label_num(double v) {
  if (std::abs(v) < 1e-12) {
    v = 0.0;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double nice_step(double range) {
  if (!(range > 0)) {
    return 1.0;
  }
  const double raw = range / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void settle() {
    if (!(lo <= hi)) {
      lo = 0.0;
      hi = 1.0;
    }
    if (hi - lo < 1e-12) {
      lo -= 0.5;
      hi += 0.5;
    }
  }
};

// Indices of the points to draw: all if few, else first/min/max/last per pixel column.
std::vector<std::size_t> decimate(const Series& s, double x0, double sx, std::size_t max_points) {
  std::vector<std::size_t> keep;
  const std::size_t n = s.x.size();
  if (n <= max_points) {
    keep.reserve(n);
    for (std::size_t i = 0; i < n; ++i) keep.push_back(i);
    return keep;
  }
  std::size_t i = 0;
  while (i < n) {
    const auto col = static_cast<long long>(std::floor((s.x[i] - x0) * sx));
    std::size_t j = i;
    std::size_t mn = i;
    std::size_t mx = i;
    while (j < n && static_cast<long long>(std::floor((s.x[j] - x0) * sx)) == col) {
      if (s.y[j] < s.y[mn]) mn = j;
      if (s.y[j] > s.y[mx]) mx = j;
      ++j;
    }
    std::vector<std::size_t> b{i, mn, mx, j - 1};
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
    keep.insert(keep.end(), b.begin(), b.end());
    i = j;
  }
  return keep;
}

}  // namespace

void write_svg(std::ostream& os, std::string_view title, std::span<const Panel> panels, SvgOptions opt) {
  for (const Panel& p : panels) {
    for (const Series& s : p.series) {
      if (s.x.size() != s.y.size()) {
        throw std::invalid_argument("svg: series '" + s.label + "' has different x and y lengths");
      }
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
          throw std::invalid_argument("svg: series '" + s.label + "' has a non-finite value");
        }
      }
    }
  }
  const double W = opt.width;
  const double PH = opt.panel_height;
  const double top = 40.0;
  const double ml = 80.0, mr = 30.0, mt = 30.0, mb = 50.0;
  const double H = top + PH * static_cast<double>(panels.size()) + 10.0;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << opt.width << "\" height=\""
     << num(H) << "\" viewBox=\"0 0 " << opt.width << ' ' << num(H) << "\" font-family=\"sans-serif\">\n"
     << "<title>" << esc(title) << "</title>\n"
     << "<rect x=\"0\" y=\"0\" width=\"" << opt.width << "\" height=\"" << num(H) << "\" fill=\"white\"/>\n"
     << "<text x=\"" << num(W / 2) << "\" y=\"26\" font-size=\"18\" text-anchor=\"middle\">" << esc(title)
     << "</text>\n";
  for (std::size_t pi = 0; pi < panels.size(); ++pi) {
    const Panel& p = panels[pi];
    const double oy = top + PH * static_cast<double>(pi);
    const double px0 = ml, px1 = W - mr, py0 = oy + mt, py1 = oy + PH - mb;
    Range rx, ry;
    for (const Series& s : p.series) {
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        rx.add(s.x[i]);
        ry.add(s.y[i]);
      }
    }
    rx.settle();
    ry.settle();
    const double ystep = nice_step(ry.hi - ry.lo);
    ry.lo = std::floor(ry.lo / ystep) * ystep;
    ry.hi = std::ceil(ry.hi / ystep) * ystep;
    const double xstep = nice_step(rx.hi - rx.lo);
    const double sx = (px1 - px0) / (rx.hi - rx.lo);
    const double sy = (py1 - py0) / (ry.hi - ry.lo);
    auto X = [&](double v) { return px0 + (v - rx.lo) * sx; };
    auto Y = [&](double v) { return py1 - (v - ry.lo) * sy; };
    os << "<g class=\"panel\" id=\"panel" << pi << "\">\n"
       << "<text x=\"" << num(px0) << "\" y=\"" << num(oy + 20) << "\" font-size=\"14\">" << esc(p.title)
       << "</text>\n";
    // grid + ticks
    os << "<g class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\">\n";
    for (double v = std::ceil(rx.lo / xstep) * xstep; v <= rx.hi + xstep * 1e-9; v += xstep) {
      os << "<line x1=\"" << num(X(v)) << "\" y1=\"" << num(py0) << "\" x2=\"" << num(X(v)) << "\" y2=\""
         << num(py1) << "\"/>\n";
    }
    for (double v = ry.lo; v <= ry.hi + ystep * 1e-9; v += ystep) {
      os << "<line x1=\"" << num(px0) << "\" y1=\"" << num(Y(v)) << "\" x2=\"" << num(px1) << "\" y2=\""
         << num(Y(v)) << "\"/>\n";
    }
    os << "</g>\n<g class=\"ticks\" font-size=\"11\" fill=\"#333333\">\n";
    for (double v = std::ceil(rx.lo / xstep) * xstep; v <= rx.hi + xstep * 1e-9; v += xstep) {
      os << "<text x=\"" << num(X(v)) << "\" y=\"" << num(py1 + 16) << "\" text-anchor=\"middle\">"
         << label_num(v) << "</text>\n";
    }
    for (double v = ry.lo; v <= ry.hi + ystep * 1e-9; v += ystep) {
      os << "<text x=\"" << num(px0 - 6) << "\" y=\"" << num(Y(v) + 4) << "\" text-anchor=\"end\">"
         << label_num(v) << "</text>\n";
    }
    os << "</g>\n"
       << "<rect x=\"" << num(px0) << "\" y=\"" << num(py0) << "\" width=\"" << num(px1 - px0) << "\" height=\""
       << num(py1 - py0) << "\" fill=\"none\" stroke=\"black\"/>\n"
       << "<text x=\"" << num((px0 + px1) / 2) << "\" y=\"" << num(py1 + 38) << "\" font-size=\"12\" "
       << "text-anchor=\"middle\">" << esc(p.x_label) << "</text>\n"
       << "<text x=\"" << num(px0 - 58) << "\" y=\"" << num((py0 + py1) / 2) << "\" font-size=\"12\" "
       << "text-anchor=\"middle\" transform=\"rotate(-90 " << num(px0 - 58) << ' ' << num((py0 + py1) / 2)
       << ")\">" << esc(p.y_label) << "</text>\n";
    for (std::size_t si = 0; si < p.series.size(); ++si) {
      const Series& s = p.series[si];
      const std::string color = s.color.empty() ? kPalette[si % std::size(kPalette)] : s.color;
      os << "<polyline class=\"series\" data-label=\"" << esc(s.label) << "\" fill=\"none\" stroke=\"" << esc(color)
         << "\" stroke-width=\"1.5\"" << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << " points=\"";
      bool first = true;
      for (const std::size_t i : decimate(s, rx.lo, sx, opt.max_points)) {
        os << (first ? "" : " ") << num(X(s.x[i])) << ',' << num(Y(s.y[i]));
        first = false;
      }
      os << "\"/>\n";
      const double ly = py0 + 14 + 16 * static_cast<double>(si);
      os << "<line x1=\"" << num(px1 - 170) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(px1 - 150)
         << "\" y2=\"" << num(ly - 4) << "\" stroke=\"" << esc(color) << "\" stroke-width=\"2\"/>\n"
         << "<text x=\"" << num(px1 - 145) << "\" y=\"" << num(ly) << "\" font-size=\"11\">" << esc(s.label)
         << "</text>\n";
    }
    os << "</g>\n";
  }
  os << "</svg>\n";
}

void write_motion_svg(std::ostream& os, std::string_view title, std::span<const MotionTrace> traces,
                      SvgOptions opt) {
  Panel pos{"Position", "t [s]", "position [mm]", {}};
  Panel spd{"Speed", "t [s]", "speed [mm/s]", {}};
  for (const MotionTrace& t : traces) {
    pos.series.push_back(Series{t.label, t.t_s, t.pos_mm, {}, false});
    spd.series.push_back(Series{t.label, t.t_s, t.speed_mm_s, {}, false});
  }
  const Panel panels[] = {pos, spd};
  write_svg(os, title, panels, opt);
}

}  // namespace ap::model::waveform
