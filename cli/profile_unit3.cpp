// The 3-axis USB unit (seed 001) as a profile (docs/profiles.md, docs/unit3.md). So far it
// brings its wire dialect (protocol/unit3_wire): `frame decode --profile unit3` reads its
// captures, and its tests, fuzz target and mutants carry the unit3 label. The parts it has not
// brought yet (core, simulated board, proofs, size check) are empty here, and the commands
// that need them say so instead of running something else.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"
#include "models/smt/modules.hpp"
#include "profile.hpp"
#include "protocol/unit3_wire/dialect.hpp"

namespace ap::cli {

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

}  // namespace

Profile unit3_profile() {
  return Profile{
      .name = "unit3",
      .title = "3-axis USB control unit",
      .seed = "seed-001 (docs/unit3.md)",
      .mcu = "ATmega2560 (256 KB flash, 8 KB RAM)",
      .decode_frames = &decode_frames,
      .decode_stream = &decode_stream,
      .encode = nullptr,
      .doc = nullptr,
      .scenarios = "scenarios/unit3",
      .sim_run = nullptr,
      .sim_board = nullptr,
      .obligations = &model::smt::unit3_obligations,
      .coverage_paths = {"protocol/unit3_wire", "core/unit3_joystick", "core/unit3_axis", "core/unit3_settings",
                         "core/unit3_ramp", "core/unit3_menu", "core/unit3_board"},
      // Cross-built for the Cortex-M4 and held to the ATmega2560's budget (docs/unit3.md "MCU").
      .size_check = "ci/m4-build --profile unit3",
      .size_tag = "m4-unit3",
  };
}

}  // namespace ap::cli
