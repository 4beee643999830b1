// The HC08 single-motor unit (seed 002) as a profile (docs/profiles.md, docs/hc08.md). It has no
// link to a PC (its only input is the keypad), so it brings no wire codec: `frame` says so. Its
// end-to-end runs drive the keys over the bus and read the coil lines.
#include "cli.hpp"
#include "models/smt/modules.hpp"
#include "profile.hpp"

namespace ap::cli {

Profile hc08_profile() {
  return Profile{
      .name = "hc08",
      .title = "HC08 single-motor unit",
      .seed = "seed-002 (docs/hc08.md)",
      .mcu = "MC68HC908LJ12 (12 KB flash, 512 B RAM)",
      .decode_frames = nullptr,
      .decode_stream = nullptr,
      .encode = nullptr,
      .doc = nullptr,
      .scenarios = "scenarios/hc08",
      .sim_run = nullptr,
      .sim_board = nullptr,
      .obligations = &model::smt::hc08_obligations,
      .coverage_paths = {"core/hc08_drive", "core/hc08_timer", "core/hc08_motor", "core/hc08_menu", "core/hc08_board"},
      // Cross-built for the Cortex-M4 and held to the HC08's budget (docs/hc08.md "MCU").
      .size_check = "ci/m4-build --profile hc08",
      .size_tag = "m4-hc08",
  };
}

}  // namespace ap::cli
