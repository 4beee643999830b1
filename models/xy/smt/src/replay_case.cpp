#include "models/xy/smt/replay_case.hpp"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ap::model::smt {

std::string format_case(const ReplayCase& k) {
  std::ostringstream o;
  o << "# written by axisproof prove; replayed by properties/xy/smt/smt_replay_test.cpp\n";
  o << "obligation " << k.obligation << "\nkind " << k.kind << "\n";
  if (k.kind == "timer") {
    o << "timer " << k.timer_f << "\n";
    return o.str();
  }
  if (k.kind == "table" || k.kind == "watchdog") return o.str();  // the replay checks the whole function
  const auto& c = k.config;
  o << "config " << c.v_start << ' ' << c.v_slow << ' ' << c.v_fast << ' ' << c.accel << ' ' << c.soft_min << ' '
    << c.soft_max << ' ' << c.home_travel << ' ' << c.home_position << "\n";
  const auto& s = k.state;
  o << "state " << int(s.phase) << ' ' << int(s.mode) << ' ' << int(s.dir) << ' ' << int(s.jog_dir) << ' '
    << int(s.level) << ' ' << int(s.latch_min) << ' ' << int(s.latch_max) << ' ' << int(s.homed) << ' ' << s.pos
    << ' ' << s.target << ' ' << s.v << ' ' << s.frac << "\n";
  for (const auto& in : k.inputs) {
    o << "input " << int(in.cmd.kind) << ' ' << int(in.cmd.dir) << ' ' << int(in.cmd.level) << ' ' << in.cmd.value
      << ' ' << int(in.endstop_min) << ' ' << int(in.endstop_max) << ' ' << int(in.blocked) << ' '
      << int(in.link_alive) << "\n";
  }
  o << "run " << k.run << "\n";
  return o.str();
}

std::string write_case(const ReplayCase& k) {
  const char* env = std::getenv("AP_PROVE_OUT");
  const std::filesystem::path dir = env != nullptr ? std::filesystem::path(env) : std::filesystem::path("out/prove");
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path file = dir / (k.obligation + ".case");
  std::ofstream(file) << format_case(k);
  return file.string();
}

bool read_case(const std::string& path, ReplayCase& out, std::string& error) {
  std::ifstream f(path);
  if (!f) {
    error = "cannot open " + path;
    return false;
  }
  out = ReplayCase{};
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "obligation") {
      in >> out.obligation;
    } else if (key == "kind") {
      in >> out.kind;
    } else if (key == "timer") {
      in >> out.timer_f;
    } else if (key == "run") {
      in >> out.run;
    } else if (key == "config") {
      auto& c = out.config;
      in >> c.v_start >> c.v_slow >> c.v_fast >> c.accel >> c.soft_min >> c.soft_max >> c.home_travel >> c.home_position;
    } else if (key == "state") {
      int p = 0, m = 0, d = 0, j = 0, l = 0, a = 0, b = 0, h = 0;
      auto& s = out.state;
      in >> p >> m >> d >> j >> l >> a >> b >> h >> s.pos >> s.target >> s.v >> s.frac;
      s.phase = static_cast<xy_axis::Phase>(p);
      s.mode = static_cast<xy_axis::Mode>(m);
      s.dir = static_cast<std::int8_t>(d);
      s.jog_dir = static_cast<std::int8_t>(j);
      s.level = static_cast<std::uint8_t>(l);
      s.latch_min = static_cast<std::uint8_t>(a);
      s.latch_max = static_cast<std::uint8_t>(b);
      s.homed = static_cast<std::uint8_t>(h);
    } else if (key == "input") {
      int k = 0, d = 0, l = 0, emin = 0, emax = 0, bl = 0, la = 0;
      xy_axis::Input x;
      in >> k >> d >> l >> x.cmd.value >> emin >> emax >> bl >> la;
      x.cmd.kind = static_cast<xy_axis::CmdKind>(k);
      x.cmd.dir = static_cast<std::int8_t>(d);
      x.cmd.level = static_cast<std::uint8_t>(l);
      x.endstop_min = static_cast<std::uint8_t>(emin);
      x.endstop_max = static_cast<std::uint8_t>(emax);
      x.blocked = static_cast<std::uint8_t>(bl);
      x.link_alive = static_cast<std::uint8_t>(la);
      out.inputs.push_back(x);
    } else {
      error = "unknown line: " + line;
      return false;
    }
    if (in.fail()) {
      error = "bad line: " + line;
      return false;
    }
  }
  return true;
}

}  // namespace ap::model::smt
