// axisproof gcode: a G-code program on the simulated XY platform (docs/cnc.md).
//   axisproof gcode FILE [--dialect thesis|tolerant] [--out ROOT] [--plan]
//       parses the program (typed errors with line and column), prints its segments and the
//       look-ahead's junctions, runs it end to end over the DDS bus on the thesis's machine
//       (20 steps/mm, v_max 50 mm/s, J 20 mm/s^3) and writes ROOT/NAME/{trace.csv, path.csv,
//       path.svg (commanded vs executed), profile.svg (speed, acceleration, jerk), ...}
//   axisproof gcode --table3
//       the thesis's Tab. 3 recurrence digit for digit, with the exact constant-jerk values
#include "cli.hpp"
#include "commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "models/xy/scurve/table3.hpp"
#include "pc/xy/gcode/program.hpp"
#include "sim/xy/run.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::cli {

namespace {

struct GcodeOptions {
  std::string file;
  std::string dialect = "tolerant";
  std::string out_root = "out/gcode";
  bool table3 = false;
  bool plan_only = false;
};

// The thesis's machine (seed-003.md §2.5, §5.3.1): 200 steps/rev, 10 mm/rev, no microsteps:
// 20 steps/mm; v_max 50 mm/s. Its S-curve has no acceleration limit; 40 mm/s^2 lies above the
// pure-jerk ramp's peak (31.6 mm/s^2), so the ramps are the thesis's.
constexpr std::int64_t kStepUm = 50;
constexpr const char* kMachine =
    "board param lead_pitch 10000\n"
    "board param steps_per_rev 200\n"
    "board param microsteps 1\n"
    "board param fast_speed 50000\n"
    "board param start_speed 500\n"
    "board param max_acceleration 40000\n"
    "board param soft_min_x 0\n"
    "board param soft_max_x 999999\n"
    "board param soft_min_y 0\n"
    "board param soft_max_y 999999\n";

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* kind_name(xy_pcgcode::SegKind k) {
  return k == xy_pcgcode::SegKind::Line ? "line" : (k == xy_pcgcode::SegKind::ArcCw ? "arc cw" : "arc ccw");
}

// An upper bound of the run: each segment rest to rest at 50 mm/s with 4 s of ramps.
double duration_s(const xy_pcgcode::Program& p) {
  double t = 2.0;
  for (const xy_pcgcode::Segment& s : p.segments) {
    double steps = static_cast<double>(std::max(std::llabs(s.x1 - s.x0), std::llabs(s.y1 - s.y0))) / kStepUm;
    if (s.kind != xy_pcgcode::SegKind::Line) steps = 5.66 * std::hypot(static_cast<double>(s.x0 - s.cx), static_cast<double>(s.y0 - s.cy)) / kStepUm + 8;
    t += steps / 1000.0 + 4.0;
  }
  return std::ceil(t);
}

void print_plan(const xy_pcgcode::Program& p) {
  std::printf("segments (um):\n");
  for (std::size_t i = 0; i < p.segments.size(); ++i) {
    const auto& s = p.segments[i];
    std::printf("  %2zu line %3u %-7s (%lld, %lld) -> (%lld, %lld)", i + 1, s.line, kind_name(s.kind),
                static_cast<long long>(s.x0), static_cast<long long>(s.y0), static_cast<long long>(s.x1),
                static_cast<long long>(s.y1));
    if (s.kind != xy_pcgcode::SegKind::Line) std::printf(" centre (%lld, %lld)", static_cast<long long>(s.cx), static_cast<long long>(s.cy));
    std::printf("%s\n", s.rapid ? " rapid" : "");
  }
  std::printf("junctions (look-ahead, docs/lookahead.md; the board keeps speed only through tangent ones):\n");
  std::printf("  after  turn [deg]  factor  thesis v [mm/s]  per-axis cap [mm/s]  kind          board\n");
  for (const auto& j : p.junctions) {
    std::printf("  %5zu  %10.3f  %6.3f  %15.2f  %19.2f  %-12s  %s\n", j.segment + 1, j.turn_mdeg / 1000.0,
                j.factor_permille / 1000.0, j.thesis_um_s / 1000.0, j.capped_um_s / 1000.0, j.kind.c_str(),
                j.continuous ? "continuous" : "stops");
  }
  for (const auto& n : p.notes) std::printf("note: %s\n", n.c_str());
}

struct XY {
  double x, y;
};

// The commanded path (the program's geometry, arcs as true circles) and the executed one
// (the board's step counters from path.csv), in mm.
void write_path_svg(const std::string& out, const xy_pcgcode::Program& p, const std::vector<XY>& done) {
  std::vector<std::vector<XY>> cmd;
  for (const auto& s : p.segments) {
    std::vector<XY> poly;
    const auto mm = [](std::int64_t um) { return static_cast<double>(um) / 1000.0; };
    const double x0 = mm(s.x0), y0 = mm(s.y0), x1 = mm(s.x1), y1 = mm(s.y1);
    if (s.kind == xy_pcgcode::SegKind::Line) {
      poly = {{x0, y0}, {x1, y1}};
    } else {
      const double cx = mm(s.cx), cy = mm(s.cy);
      const double r = std::hypot(x0 - cx, y0 - cy);
      const double a0 = std::atan2(y0 - cy, x0 - cx);
      double a1 = std::atan2(y1 - cy, x1 - cx);
      const bool cw = s.kind == xy_pcgcode::SegKind::ArcCw;
      if (cw && a1 >= a0) a1 -= 2 * M_PI;
      if (!cw && a1 <= a0) a1 += 2 * M_PI;
      for (int k = 0; k <= 180; ++k) {
        const double a = a0 + (a1 - a0) * k / 180.0;
        poly.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
      }
    }
    cmd.push_back(std::move(poly));
  }
  double lo_x = 0, hi_x = 1, lo_y = 0, hi_y = 1;
  bool first = true;
  const auto grow = [&](const XY& q) {
    if (first) {
      lo_x = hi_x = q.x;
      lo_y = hi_y = q.y;
      first = false;
    }
    lo_x = std::min(lo_x, q.x), hi_x = std::max(hi_x, q.x), lo_y = std::min(lo_y, q.y), hi_y = std::max(hi_y, q.y);
  };
  for (const auto& poly : cmd) for (const auto& q : poly) grow(q);
  for (const auto& q : done) grow(q);
  const double span = std::max({hi_x - lo_x, hi_y - lo_y, 1.0});
  const double pad = span * 0.05;
  const double size = 800;
  const auto sx = [&](double x) { return 40 + (x - lo_x + pad) / (span + 2 * pad) * size; };
  const auto sy = [&](double y) { return 40 + size - (y - lo_y + pad) / (span + 2 * pad) * size; };
  std::ofstream o(out, std::ios::trunc);
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"880\" height=\"920\" "
       "viewBox=\"0 0 880 920\">\n<rect width=\"880\" height=\"920\" fill=\"white\"/>\n"
       "<text x=\"40\" y=\"24\" font-family=\"sans-serif\" font-size=\"16\">Path in XY [mm]: commanded (blue) vs "
       "executed step counters (red, dashed)</text>\n";
  o << "<rect x=\"40\" y=\"40\" width=\"800\" height=\"800\" fill=\"none\" stroke=\"#888\"/>\n";
  char buf[128];
  for (const auto& poly : cmd) {
    o << "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"3\" points=\"";
    for (const auto& q : poly) {
      std::snprintf(buf, sizeof buf, "%.2f,%.2f ", sx(q.x), sy(q.y));
      o << buf;
    }
    o << "\"/>\n";
  }
  o << "<polyline fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"6,4\" points=\"";
  const std::size_t stride = std::max<std::size_t>(1, done.size() / 4000);
  for (std::size_t i = 0; i < done.size(); i += stride) {
    std::snprintf(buf, sizeof buf, "%.2f,%.2f ", sx(done[i].x), sy(done[i].y));
    o << buf;
  }
  o << "\"/>\n";
  std::snprintf(buf, sizeof buf, "<text x=\"40\" y=\"870\" font-family=\"sans-serif\" font-size=\"13\">x %.1f .. %.1f mm, y %.1f .. %.1f mm</text>\n",
                lo_x, hi_x, lo_y, hi_y);
  o << buf << "</svg>\n";
}

int run_gcode(const GcodeOptions& opt) {
  if (opt.table3) {
    std::fputs(model::xy_scurve::table3_report().c_str(), stdout);
    return 0;
  }
  if (opt.file.empty()) {
    std::fprintf(stderr, "axisproof gcode: give a G-code FILE or --table3\n");
    return 2;
  }
  std::string path = opt.file;
  if (!std::filesystem::is_regular_file(path) && std::filesystem::is_regular_file(source_dir() + "/" + path)) {
    path = source_dir() + "/" + path;
  }
  xy_pcgcode::Program prog;
  try {
    xy_pcgcode::Options po;
    po.dialect = opt.dialect == "thesis" ? xy_gcode::Dialect::Thesis : xy_gcode::Dialect::Tolerant;
    po.v_max_um_s = 50'000;
    po.v_jump_um_s = 500;
    prog = xy_pcgcode::translate(read_file(path), po, opt.file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof gcode: %s\n", e.what());
    return 2;
  }
  print_plan(prog);
  if (opt.plan_only) return 0;
  if (prog.segments.empty()) {
    std::fprintf(stderr, "axisproof gcode: %s has no XY motion\n", opt.file.c_str());
    return 2;
  }
  std::string name = std::filesystem::path(opt.file).stem().string();
  for (char& c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-')) c = '_';
  }
  const double d = duration_s(prog);
  std::ostringstream scn;
  scn << "scenario " << name << "\n"
      << "title \"G-code " << opt.file << " on the XY platform, the thesis's machine (docs/cnc.md)\"\n"
      << "duration " << d << " s\n"
      << "board ble session\nboard pos x 0 mm\nboard pos y 0 mm\n"
      << kMachine << "at 0.5 s gcode \"" << path << "\" " << opt.dialect << "\n"
      << "expect by " << d - 0.5 << " s x.status == reached\n"
      << "expect by " << d - 0.5 << " s y.status == reached\n"
      // One step is 50 um: the counters end exactly on the last end's nearest step.
      << "expect end x.pos == " << prog.end_x_um << " um tol 25 um\n"
      << "expect end y.pos == " << prog.end_y_um << " um tol 25 um\n"
      << "expect always x.speed <= 50 mm/s tol 0.05 mm/s\n"
      << "expect always y.speed <= 50 mm/s tol 0.05 mm/s\n"
      << "expect end gaps == 0\n";
  try {
    const sim::xy::scenario::Scenario s = sim::xy::scenario::parse(scn.str(), name + ".scn");
    sim::xy::RunOptions o;
    o.out_root = opt.out_root;
    o.log = nullptr;
    const sim::xy::RunResult r = sim::xy::run_scenario(s, o);
    std::cout << sim::xy::format_report(s, r);
    if (!r.out_dir.empty()) {
      std::ofstream(r.out_dir + "/scenario.scn", std::ios::trunc) << scn.str();
      std::vector<XY> done;
      std::ifstream pc(r.out_dir + "/path.csv");
      std::string line;
      std::getline(pc, line);
      while (std::getline(pc, line)) {
        double t = 0, x = 0, y = 0;
        if (std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &x, &y) == 3) done.push_back({x, y});
      }
      write_path_svg(r.out_dir + "/path.svg", prog, done);
      std::cout << "  outputs: " << r.out_dir
                << "/{trace.csv,path.csv,path.svg,profile.svg,plots.svg,waveforms.vcd,scenario.scn}\n";
    }
    return r.pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "axisproof gcode: %s\n", e.what());
    return 2;
  }
}

}  // namespace

void add_gcode(CLI::App& app) {
  auto opt = std::make_shared<GcodeOptions>();
  auto* sub = app.add_subcommand("gcode", "Run a G-code program on the simulated XY platform (docs/cnc.md)");
  sub->add_option("file", opt->file, "G-code file (e.g. scenarios/xy/gcode/thesis.gcode)");
  sub->add_option("--dialect", opt->dialect, "thesis (strict N.. G.. syntax) or tolerant (grbl/LinuxCNC)")
      ->check(CLI::IsMember({"thesis", "tolerant"}));
  sub->add_option("--out", opt->out_root, "output root (default out/gcode)");
  sub->add_flag("--table3", opt->table3, "print the thesis's Tab. 3 and the exact constant-jerk values");
  sub->add_flag("--plan", opt->plan_only, "parse and print the plan only, no run");
  sub->final_callback([opt] { exit_status() = run_gcode(*opt); });
}

}  // namespace ap::cli
