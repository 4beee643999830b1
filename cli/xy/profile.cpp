// The XY platform (seed 000) as the harness's first profile: its entry in the profile table
// (profile.hpp, docs/profiles.md) and the adapters behind it: the frame codec of
// docs/protocol.md for `frame`, the simulated board and PC of sim/ for `sim`, the obligations
// of models/smt for `prove`.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "models/xy/smt/modules.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "core/xy/frame/stream_framer.hpp"
#include "pc/xy/client/client.hpp"
#include "pc/xy/client/doc_tables.hpp"
#include "pc/xy/client/readable.hpp"
#include "pc/dds/bus.hpp"
#include "profile.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/xy/board.hpp"
#include "sim/xy/run.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::cli {

// Named so that the three profiles' helpers stay apart in the unity build (cli/CMakeLists.txt).
namespace profile_xy {
namespace {

// ------------------------------------------------------------------------------ frame codec

std::string printable(const std::string& s) {
  std::string out;
  for (const char c : s) {
    const auto ch = static_cast<unsigned char>(c);
    if (ch >= 0x20 && ch < 0x7F) {
      out += static_cast<char>(ch);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", ch);
      out += hex;
    }
  }
  return out;
}

// One frame given whole: its start character says which kind it is meant to be.
bool decode_one(const std::string& text, const std::string& label) {
  if (!text.empty() && text[0] == xy_codec::kEchoStart) {
    xy_frame::EchoFrame e;
    const auto r = xy_frame::parse_echo(bytes_of(text), e);
    if (!r.ok()) {
      std::printf("%s: REJECTED %s\n  bytes: %s\n", label.c_str(), xy_client::describe(r).c_str(), printable(text).c_str());
      return false;
    }
    std::printf("%s: OK %s", label.c_str(), xy_client::describe(e).c_str());
    return true;
  }
  xy_frame::CommandFrame c;
  const auto r = xy_frame::parse_command(bytes_of(text), c);
  if (!r.ok()) {
    std::printf("%s: REJECTED %s\n  bytes: %s\n", label.c_str(), xy_client::describe(r).c_str(), printable(text).c_str());
    return false;
  }
  std::printf("%s: OK %s", label.c_str(), xy_client::describe(c).c_str());
  return true;
}

struct Report {
  std::uint32_t offset;
  std::string text;
  bool ok;
};

// A capture may hold commands, echoes, whitespace between them and garbage; every
// non-whitespace byte that is in no frame is reported, so nothing is silently skipped.
bool decode_stream(const std::string& data) {
  std::vector<Report> reports;
  std::vector<bool> covered(data.size(), false);
  const auto cover = [&](std::uint32_t at, std::size_t n) {
    for (std::size_t i = at; i < at + n && i < covered.size(); ++i) covered[i] = true;
  };
  xy_frame::CommandFramer commands;
  commands.feed(bytes_of(data), [&](const xy_frame::CommandFramer::Event& e) {
    cover(e.stream_offset, e.length);
    const std::string where = "byte " + std::to_string(e.stream_offset);
    reports.push_back({e.stream_offset,
                       e.rejection.ok() ? where + ": OK " + xy_client::describe(e.frame)
                                        : where + ": REJECTED command, " + xy_client::describe(e.rejection) + "\n",
                       e.rejection.ok()});
  });
  xy_frame::EchoFramer echoes;
  echoes.feed(bytes_of(data), [&](const xy_frame::EchoFramer::Event& e) {
    cover(e.stream_offset, e.length);
    const std::string where = "byte " + std::to_string(e.stream_offset);
    reports.push_back({e.stream_offset,
                       e.rejection.ok() ? where + ": OK " + xy_client::describe(e.frame)
                                        : where + ": REJECTED echo, " + xy_client::describe(e.rejection) + "\n",
                       e.rejection.ok()});
  });
  for (const auto pending : {commands.pending(), echoes.pending()}) {
    if (pending == 0) continue;
    const auto at = static_cast<std::uint32_t>(data.size() - pending);
    cover(at, pending);
    reports.push_back({at, "byte " + std::to_string(at) + ": REJECTED incomplete frame at end of input (" +
                               std::to_string(pending) + " bytes)\n", false});
  }
  for (std::size_t i = 0; i < data.size();) {
    const bool space = data[i] == ' ' || data[i] == '\n' || data[i] == '\r' || data[i] == '\t';
    if (covered[i] || space) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < data.size() && !covered[j]) ++j;
    reports.push_back({static_cast<std::uint32_t>(i),
                       "byte " + std::to_string(i) + ": GARBAGE " + printable(data.substr(i, j - i)) + "\n", false});
    i = j;
  }
  std::stable_sort(reports.begin(), reports.end(), [](const Report& a, const Report& b) { return a.offset < b.offset; });
  bool all_ok = true;
  for (const auto& r : reports) {
    std::fputs(r.text.c_str(), stdout);
    all_ok = all_ok && r.ok;
  }
  const auto accepted = commands.counters().accepted_frames + echoes.counters().accepted_frames;
  std::printf("%u frame(s) decoded, %zu problem(s)\n", accepted,
              static_cast<std::size_t>(std::count_if(reports.begin(), reports.end(), [](const Report& r) { return !r.ok; })));
  return all_ok && accepted > 0;
}


bool decode_frames(const std::vector<std::string>& frames) {
  bool ok = true;
  for (std::size_t i = 0; i < frames.size(); ++i) ok = decode_one(frames[i], "frame " + std::to_string(i + 1)) && ok;
  return ok;
}

int encode(const std::vector<std::string>& tokens) {
  std::string text;
  for (const auto& t : tokens) text += t + " ";
  xy_frame::CommandFrame f;
  const auto err = xy_client::parse_readable(text, f);
  if (!err.empty()) {
    std::fprintf(stderr, "axisproof frame encode: %s\n", err.c_str());
    return 1;
  }
  const auto bytes = xy_client::format(f);
  if (!bytes) {
    std::fprintf(stderr, "axisproof frame encode: frame does not validate\n");
    return 1;
  }
  std::printf("%s\n", bytes->c_str());
  return 0;
}

void doc() { std::fputs(xy_client::all_tables_md().c_str(), stdout); }

// -------------------------------------------------------------------------------- simulator

int sim_board(const SimBoardArgs& a) {
  return host_boards(a, "xy", [](const dds::ParticipantPtr& pp, std::uint32_t id, const std::string& out, std::chrono::seconds idle) {
    sim::xy::BoardOptions o;
    o.id = id;
    o.out_dir = out;
    return sim::xy::serve_board(pp, o, idle);
  });
}

int sim_run(const SimRunArgs& a) {
  return sim_run_main([&]() -> SimRunVerdict {
    sim::xy::scenario::Scenario s = sim::xy::scenario::parse_file(a.scenario);
    sim::xy::RunOptions o;
    o.realtime = a.realtime || s.timing == sim::xy::scenario::Timing::realtime;
    set_run_options(a, o);
    o.out_root = a.out_root;
    if (a.target == "qemu") {
      if (a.join) throw std::runtime_error("--target qemu runs its own boards: no --join");
      o.qemu_image = xy_qemu_image();
    } else if (a.target != "host") {
      throw std::runtime_error("--target " + a.target + ": host or qemu");
    }
    if (o.step_us <= 0 || s.period_us % o.step_us != 0) throw std::runtime_error("--step-ms must divide the command period");
    const sim::xy::RunResult r = sim::xy::run_scenario(s, o);
    std::cout << sim::xy::format_report(s, r);
    return {r.pass, r.out_dir};
  });
}

}  // namespace
}  // namespace profile_xy

// The XY board's QEMU image (docs/qemu.md), built in the m4 tree first if needed.
std::string xy_qemu_image() {
  if (!ensure_built("m4", {"ap_xy_qemu"}, true)) throw std::runtime_error("building the QEMU image (m4 preset) failed");
  return build_dir("m4") + "/firmware/xy/ap_xy_qemu.elf";
}


// Its adapters; the declaration (profiles/xy.cmake) fills in the rest of its entry.
Profile ap_profile_xy() {
  Profile p;
  p.decode_frames = &profile_xy::decode_frames;
  p.decode_stream = &profile_xy::decode_stream;
  p.encode = &profile_xy::encode;
  p.doc = &profile_xy::doc;
  p.sim_run = &profile_xy::sim_run;
  p.sim_board = &profile_xy::sim_board;
  p.panel = &xy_panel;
  p.obligations = &model::smt::xy_obligations;
  p.registry_tests =
      "^(tmc2130_proof\\.every_field_obligation_is_proved|smt_proof\\.(axis|timer|storage)_obligations_proved|(Interp|Scurve)"
      "Proof\\.EveryObligationIsProved)$";
  // docs/qemu.md "The gate stage": an absolute move, the BLE pins and the LED, the button's
  // shutdown and the KillSwitch, a reversal, an endstop, a link loss, a parameter save across a
  // reboot, the IHOLD_IRUN shadow register, and the I2C sensors.
  p.qemu_scenarios = {"absolute_20mm",  "ble_led",           "shutdown_button", "manual_reversal", "endstop_hit",
                      "link_loss_jog",  "accel_save_reboot", "ihold_irun",      "sensors"};
  p.add_commands = [](CLI::App& app) {
    add_regs(app);
    add_gcode(app);
  };
  return p;
}

}  // namespace ap::cli
