// The simulated board's output files (docs/sim.md "Outputs (board 0) under out/sim/xy/NAME/";
// board 0 alone, with an out_dir): the waveforms of its pins and buses (waveforms.vcd), one
// trace.csv row per tick and axis with the lost-step risk of the mechanics model, plots.svg,
// and the coordinated path's path.csv and profile.svg (docs/cnc.md). None of them feeds back
// into what the board sees.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "sim/xy/board.hpp"

namespace ap::sim::xy {
namespace {

namespace wf = ap::model::waveform;
namespace mech = ap::model::xy_mechanics;

}  // namespace

void SimBoard::open_outputs() {
  if (opt_.out_dir.empty() || !opt_.waveforms) return;
  std::filesystem::create_directories(opt_.out_dir);
  vcd_file_ = std::make_unique<std::ofstream>(opt_.out_dir + "/waveforms.vcd", std::ios::trunc);
  wf::BoardWaveformConfig cfg;
  cfg.uart_baud = opt_.baud;
  wave_ = std::make_unique<wf::BoardWaveforms>(*vcd_file_, cfg);
}

void SimBoard::wave_boot_encoders() {
  if (!wave_) return;
  // The encoders are read over SPI at power-up (eq. 7-2 seeds the step counters).
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    xy_board::Inputs in;
    fill_inputs(in);
    const auto& e = in.encoder[a];
    const std::uint32_t word = (static_cast<std::uint32_t>(e.turns) & 0xFFFFU) << 16 | e.counts;
    const std::array<std::uint8_t, 4> miso{static_cast<std::uint8_t>(word >> 24), static_cast<std::uint8_t>(word >> 16),
                                           static_cast<std::uint8_t>(word >> 8), static_cast<std::uint8_t>(word)};
    const std::array<std::uint8_t, 4> mosi{};
    (void)wave_->spi(kDevEncX + a, static_cast<std::uint64_t>(now_us_) * 1000U, mosi, miso);
  }
}

void SimBoard::wave_motor(std::size_t a, std::int64_t t0_ns, const xy_board::MotorOutput& o,
                          const std::vector<std::int64_t>& edges) {
  if (!wave_) return;
  const bool dir = o.dir > 0;
  if (dir != wave_dir_[a] || ticks_ == 0) wave_->dir(a, static_cast<std::uint64_t>(t0_ns), dir);
  if (o.enable != wave_ena_[a] || ticks_ == 0) wave_->ena(a, static_cast<std::uint64_t>(t0_ns), o.enable);
  wave_dir_[a] = dir;
  wave_ena_[a] = o.enable;
  for (const std::int64_t e : edges) wave_->step(a, static_cast<std::uint64_t>(e));
}

void SimBoard::wave_expander() {
  const std::uint16_t w = expander_word();
  if (w != expander_last_ && wave_) {
    // MCP23S17-style read of GPIOA/B after the interrupt line fired.
    const std::array<std::uint8_t, 4> mosi{0x41, 0x12, 0, 0};
    const std::array<std::uint8_t, 4> miso{0, 0, static_cast<std::uint8_t>(w & 0xFFU), static_cast<std::uint8_t>(w >> 8)};
    (void)wave_->spi(kDevExpander, static_cast<std::uint64_t>(ticks_) * kNsPerTick + 300'000U, mosi, miso);
  }
  expander_last_ = w;
}

void SimBoard::trace_tick() {
  const xy_board::Board& b = *board_;
  const std::int64_t t_us = static_cast<std::int64_t>(ticks_) * 1000;
  const std::uint8_t led_now = led();
  const double um_per_ustep =
      static_cast<double>(b.mechanics().pitch_um) / (static_cast<double>(b.mechanics().steps_per_rev) * b.mechanics().microsteps);
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    const auto ax = static_cast<xy_board::Axis>(a);
    const xy_axis::State& s = b.axis_state(ax);
    const xy_board::MotorOutput& o = b.motor_output(ax);
    const xy_board::Inputs& in = b.inputs();
    if (!opt_.out_dir.empty()) {
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "%lld,%c,%s,%s,%d,%d,%d,%d,%u,%u,%d,%d,%c,%d,%d,%d,%d,%u,%d,%d,%s,%.3f,%d,%u,%d,%d,%lld,0x%03x",
                    static_cast<long long>(t_us), a == 0 ? 'X' : 'Y', xy_axis::phase_name(s.phase), xy_axis::mode_name(s.mode),
                    s.pos, s.target, s.v / xy_axis::kSpeedScale, o.dir, in.endstop_min[a], in.endstop_max[a],
                    b.block() != xy_board::Block::None ? 1 : 0, o.enable ? o.steps : 0,
                    xy_axis::edge_letter(b.axis_edge(ax)), static_cast<int>(b.axis_error(ax)),
                    static_cast<int>(b.main_state()), static_cast<int>(b.block()), b.session_open() ? 1 : 0,
                    in.battery_mv, in.charger ? 1 : 0, in.usb ? 1 : 0, led_word(led_now).c_str(), carriage_um_[a],
                    in.encoder[a].turns, in.encoder[a].counts, o.enable ? 1 : 0, b.link_alive() ? 1 : 0,
                    static_cast<long long>(b.counters().dispatched_frames), expander_word());
      trace_rows_.emplace_back(buf);
    }
    if (!opt_.out_dir.empty() && (ticks_ % 5 == 0)) {
      plot_t_[a].push_back(static_cast<double>(t_us) / 1e6);
      plot_pos_[a].push_back(s.pos * um_per_ustep / 1000.0);
      plot_v_[a].push_back(s.v / static_cast<double>(xy_axis::kSpeedScale) * um_per_ustep / 1000.0 * s.dir);
    }
  }
  path_tick(um_per_ustep);
}

void SimBoard::path_tick(double um_per_ustep) {
  const xy_path::Executor& p = board_->path();
  const bool active = p.active();
  if (opt_.out_dir.empty() || (!active && !path_was_active_)) {
    path_was_active_ = active;
    return;
  }
  path_was_active_ = active;
  const xy_scurve::Kinematics k = p.kinematics();
  const double mm = um_per_ustep / 1000.0;  // one move is one step of the driving axis
  PathRow r;
  r.t_s = static_cast<double>(ticks_) / 1000.0;
  r.x_mm = board_->axis_state(xy_board::Axis::X).pos * mm;
  r.y_mm = board_->axis_state(xy_board::Axis::Y).pos * mm;
  r.carriage_x_mm = carriage_um_[0] / 1000.0;
  r.carriage_y_mm = carriage_um_[1] / 1000.0;
  r.v = static_cast<double>(k.vel_milli) / 1000.0 * mm;
  r.a = static_cast<double>(k.accel_milli) / 1000.0 * mm;
  r.j = static_cast<double>(k.jerk_milli) / 1000.0 * mm;
  path_rows_.push_back(r);
}

void SimBoard::write_path_outputs() const {
  if (path_rows_.empty()) return;
  {
    std::ofstream c(opt_.out_dir + "/path.csv", std::ios::trunc);
    c << "t_s,x_mm,y_mm,carriage_x_mm,carriage_y_mm,v_mm_s,a_mm_s2,j_mm_s3\n";
    char buf[256];
    for (const PathRow& r : path_rows_) {
      std::snprintf(buf, sizeof buf, "%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", r.t_s, r.x_mm, r.y_mm, r.carriage_x_mm,
                    r.carriage_y_mm, r.v, r.a, r.j);
      c << buf;
    }
  }
  std::array<wf::Panel, 3> panels;
  const std::array<std::pair<const char*, const char*>, 3> names{
      {{"Speed along the driving axis", "v [mm/s]"}, {"Acceleration", "a [mm/s^2]"}, {"Jerk", "j [mm/s^3]"}}};
  for (std::size_t i = 0; i < panels.size(); ++i) {
    panels[i].title = names[i].first;
    panels[i].x_label = "t [s]";
    panels[i].y_label = names[i].second;
    wf::Series s;
    s.label = names[i].second;
    for (const PathRow& r : path_rows_) {
      s.x.push_back(r.t_s);
      s.y.push_back(i == 0 ? r.v : (i == 1 ? r.a : r.j));
    }
    panels[i].series.push_back(std::move(s));
  }
  std::ofstream o(opt_.out_dir + "/profile.svg", std::ios::trunc);
  wf::write_svg(o, "Board " + std::to_string(opt_.id) + ": the path's S-curve (seed-003.md Fig. 30)", panels);
}

void SimBoard::write_outputs() {
  std::filesystem::create_directories(opt_.out_dir);
  // Lost-step risk per tick and axis, from the mechanics model over every STEP edge.
  std::array<std::vector<std::uint8_t>, xy_board::kAxes> risk;
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    risk[a].assign(ticks_ + 1, 0);
    if (rec_[a].edges_ns.empty()) continue;
    const mech::Result res = mechanics(a);
    for (const mech::Sample& s : res.samples) {
      const auto k = static_cast<std::size_t>(std::max(0.0, std::floor(s.t * 1000.0)));
      if (k < risk[a].size()) risk[a][k] = std::max(risk[a][k], static_cast<std::uint8_t>(s.risk));
    }
  }
  {
    std::ofstream t(opt_.out_dir + "/trace.csv", std::ios::trunc);
    t << kTraceHeader
      << ",main_state,block,session,battery_mv,charger,usb,led,carriage_um,enc_turns,enc_counts,ena,link_alive,"
         "dispatched,gpio,lost_step_risk\n";
    for (std::size_t i = 0; i < trace_rows_.size(); ++i) {
      const std::size_t tick = i / xy_board::kAxes;
      const std::size_t a = i % xy_board::kAxes;
      t << trace_rows_[i] << ',' << mech::to_string(static_cast<mech::Risk>(risk[a][tick])) << '\n';
    }
  }
  {
    std::vector<wf::MotionTrace> traces;
    for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
      wf::MotionTrace m;
      m.label.assign(1, a == 0 ? 'X' : 'Y');   // not operator=(const char*): gcc 12 -O3 -Wrestrict false positive
      m.t_s = plot_t_[a];
      m.pos_mm = plot_pos_[a];
      m.speed_mm_s = plot_v_[a];
      traces.push_back(std::move(m));
    }
    std::ofstream s(opt_.out_dir + "/plots.svg", std::ios::trunc);
    wf::write_motion_svg(s, "Board " + std::to_string(opt_.id) + ": position and speed", traces);
  }
  write_path_outputs();
  if (wave_) {
    wave_->finish();
    vcd_file_->flush();
  }
}

}  // namespace ap::sim::xy
