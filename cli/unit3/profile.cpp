// The 3-axis USB unit (seed 001) as a profile (docs/profiles.md, docs/unit3.md). So far it
// brings its wire dialect (protocol/unit3/wire): `frame decode --profile unit3` reads its
// captures, and its tests, fuzz target and mutants carry the unit3 label; `sim run` and
// `sim board --profile unit3` run its simulated unit over the DDS bus (docs/unit3-sim.md). The
// parts it has not brought yet are empty here, and the commands that need them say so instead
// of running something else.
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "core/unit3/board/unit.hpp"
#include "models/unit3/obligations.hpp"
#include "profile.hpp"
#include "protocol/unit3/wire/dialect.hpp"
#include "sim/unit3/unit3.hpp"

namespace ap::cli {

// Named so that the three profiles' helpers stay apart in the unity build (cli/CMakeLists.txt).
namespace profile_unit3 {
namespace {

namespace w = ap::unit3_wire;

const char* axis_name(w::Axis a) { return a == w::Axis::X ? "X" : a == w::Axis::Y ? "Y" : "Z"; }

std::string describe(const w::Command& c) {
  const auto three = [](const auto& v, auto show) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += std::string(i ? " " : "") + "XYZ"[i] + "=" + show(v[i]);
    return s;
  };
  switch (c.kind) {
    case w::Kind::Direction: return "direction " + three(c.sign, [](std::int8_t s) { return std::string(s > 0 ? "+" : "-"); });
    case w::Kind::Move:
      return std::string("move ") + axis_name(c.axis) + " by " + std::to_string(c.count) + " counts (1/32 step)";
    case w::Kind::StepMode:
      return "step mode " + three(c.digit, [](std::uint8_t d) { return "1/" + std::to_string(1U << d); });
    case w::Kind::Thread: return "thread " + three(c.digit, [](std::uint8_t d) { return "index " + std::to_string(d); });
    case w::Kind::Clear: return "clear the step counters";
    case w::Kind::Get: return "get the stored settings";
  }
  return "?";
}

bool decode_line(const std::string& text, const std::string& label) {
  if (const auto r = w::parse_report(bytes_of(text))) {
    std::printf("%s: OK report %s counter %lld\n", label.c_str(), axis_name(r->axis), static_cast<long long>(r->count));
    return true;
  }
  if (const auto code = w::parse_error(bytes_of(text))) {
    // A refusal: the line's own error (01..07) or the unit's (docs/unit3.md "Replies").
    const char* unit = unit3_board::refusal_key(*code);
    const bool line_error = *code <= static_cast<std::uint8_t>(w::Error::TooLong);
    if (unit == nullptr && !line_error) {
      std::printf("%s: REJECTED unknown refusal code %u\n", label.c_str(), static_cast<unsigned>(*code));
      return false;
    }
    std::printf("%s: OK refusal E%02u %s\n", label.c_str(), static_cast<unsigned>(*code),
                unit != nullptr ? unit : w::error_key(static_cast<w::Error>(*code)));
    return true;
  }
  w::Command c;
  const w::Rejection r = w::parse(bytes_of(text), c);
  if (!r.ok()) {
    std::printf("%s: REJECTED %s at byte %u\n", label.c_str(), w::error_key(r.error), static_cast<unsigned>(r.offset));
    return false;
  }
  std::printf("%s: OK %s\n", label.c_str(), describe(c).c_str());
  return true;
}

bool decode_frames(const std::vector<std::string>& lines) {
  bool ok = true;
  for (std::size_t i = 0; i < lines.size(); ++i) ok = decode_line(lines[i], "line " + std::to_string(i + 1)) && ok;
  return ok;
}

// A capture of the PC's side of the line (commands); counter reports are decoded one per
// argument. Every byte that ends in no command is reported.
bool decode_stream(const std::string& capture) {
  w::Framer f;
  bool ok = true;
  f.feed(bytes_of(capture), [&](const w::Framer::Event& e) {
    if (e.rejection.ok()) {
      std::printf("byte %u: OK %s\n", e.stream_offset, describe(e.command).c_str());
    } else {
      std::printf("byte %u: REJECTED %s at byte %u of the line\n", e.stream_offset, w::error_key(e.rejection.error),
                  static_cast<unsigned>(e.rejection.offset));
      ok = false;
    }
  });
  if (f.pending() != 0) {
    std::printf("REJECTED incomplete line at end of input (%zu bytes, no ';')\n", f.pending());
    ok = false;
  }
  const auto n = f.counters();
  std::printf("%u command(s) decoded, %u rejected\n", n.accepted, n.rejected + (f.pending() != 0 ? 1U : 0U));
  return ok && n.accepted > 0;
}

// axisproof sim board --profile unit3: boards for `sim run --profile unit3 --join --domain N`
// (docs/unit3-sim.md). Each starts from the default EEPROM image: a joined run cannot pass its
// scenario's `eeprom` line over the bus before the board exists.
int sim_board(const SimBoardArgs& a) {
  return host_boards(a, "unit3", [](const dds::ParticipantPtr& pp, std::uint32_t id, const std::string& out, std::chrono::seconds idle) {
    ap::sim::unit3::BoardOptions o;
    o.id = id;
    o.out_dir = out;
    return ap::sim::unit3::serve_board(pp, o, idle);
  });
}

// axisproof sim run --profile unit3 scenarios/unit3/NAME.scn: exit 0 pass, 1 fail, 2 error.
int sim_run(const SimRunArgs& a) {
  namespace u3 = ap::sim::unit3;
  return sim_run_main([&]() -> SimRunVerdict {
    const u3::Scenario s = u3::parse_file(a.scenario);
    if (a.realtime) throw std::runtime_error("--realtime: the unit3 run has no realtime mode");
    u3::RunOptions o;
    set_run_options(a, o);
    if (a.join && s.eeprom != u3::Eeprom::Default) throw std::runtime_error("--join: a joined board starts from the default EEPROM");
    o.out_root = a.out_root;
    if (o.step_us <= 0) throw std::runtime_error("--step-ms must be positive");
    const u3::RunResult r = u3::run_scenario(s, o);
    std::cout << u3::format_report(s, r);
    return {r.pass, r.out_dir};
  });
}

}  // namespace
}  // namespace profile_unit3

// Its adapters; the declaration (profiles/unit3.cmake) fills in the rest of its entry.
Profile ap_profile_unit3() {
  // No frame encoder or protocol page of its own; no bootable image yet (docs/unit3.md "MCU").
  Profile p;
  p.decode_frames = &profile_unit3::decode_frames;
  p.decode_stream = &profile_unit3::decode_stream;
  p.sim_run = &profile_unit3::sim_run;
  p.sim_board = &profile_unit3::sim_board;
  p.panel = &unit3_panel;
  p.obligations = &model::smt::unit3_obligations;
  p.registry_tests = "^Unit3Proofs\\.EveryObligationIsProved$";
  return p;
}

}  // namespace ap::cli
