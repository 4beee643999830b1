// The HC08 unit (core/hc08/board) driven by button sequences (docs/hc08.md). Each input byte:
//   0x00-0x9F  key (b % 5, or one of the unused codes when b >= 0x50) held for 20..51 ms of
//              scans with bounce at both ends, then released for 25 ms; main loop after each ms
//   0xA0-0xFF  (b - 0x9F) x 16 timer periods of running time
// Oracles: no crash or UB; after every key the menu, settings and display (the adjusted mark
// included) are the reference model's (models/hc08), the angle shown the one the coils put the
// rotor at (CoilTracker, docs/hc08.md "Angle arithmetic"); the coils show a table pattern; the
// motor never steps faster than its maximum frequency, changes direction only at or below the
// start frequency, and stops only from at or below it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/hc08/board/board.hpp"
#include "models/hc08/angle_model.hpp"
#include "models/hc08/menu_model.hpp"

namespace {

namespace b = ap::hc08_board;

void require(bool ok) {
  if (!ok) std::abort();
}

constexpr std::uint8_t kCodes[5] = {0x2D, 0x4D, 0x1D, 0x2B, 0x2E};  // SET LEFT RIGHT PLUS MINUS
constexpr std::uint8_t kUnused[4] = {0x4E, 0x1E, 0x47, 0x17};

constexpr std::uint32_t kBus = 2'457'600;

struct Rig {
  b::Board u;
  ap::model::hc08::MenuModel m;
  ap::model::hc08::CoilTracker coils;  // the rotor's position from every pattern the port takes
  int last_dir = 0;
  std::uint32_t last_period = 0;

  void check_display() {
    static const char* const kName[] = {"S_DEF", "SET_DRIVE", "SET_DIRECT", "SET_SPEED", "SET_ANGLE", "SET_SPEEDx", "SET_ANGLEx"};
    require(m.state() == kName[static_cast<int>(u.menu().state)]);
    require(u.display().indicator == m.indicator());
    require(coils.ok());
    require(static_cast<int>(u.display().value) == m.value(coils.angle_tenths()));
    require(u.settings().speed_centi == m.speed() && u.settings().angle_deg == m.angle());
    require(u.display().adjusted == m.adjusted());  // a speed outside the motor's range is fitted to it
  }
  void step() {
    if (!u.timer_running()) return;
    const std::uint32_t p = u.period_ticks();
    const bool half = u.motor().drive() == ap::hc08_drive::Drive::Half;
    require(p >= kBus / (half ? 1700U : 800U));  // never past the motor's maximum
    const std::uint32_t start_period = kBus / (half ? 560U : 280U);
    const int dir = u.motor().dir();
    if (last_dir != 0 && dir != last_dir) require(last_period >= start_period || p >= start_period);
    u.timer_match();
    coils.feed(u.port());
    if (!u.timer_running()) require(p >= start_period || u.settings().speed_centi * (half ? 80U : 40U) <= (half ? 56000U : 28000U));
    const std::uint8_t pat = u.motor().pattern();
    require(pat != 0 && pat != 0b0101 && pat != 0b1010 && (pat & 0xF0) == 0);
    last_dir = dir;
    last_period = p;
  }
  // A key held `ms` with bounce; the model sees it once, on the press.
  void key(std::uint8_t code, int known_key, int ms) {
    bool pressed = false;
    for (int t = 0; t < ms + 30; ++t) {
      const bool bounce = t < 6 || (t >= ms && t < ms + 5);
      const std::uint8_t sample = t < ms ? (bounce && (t % 2) ? 0 : code) : (bounce && (t % 2) ? code : 0);
      const bool running = u.timer_running();
      u.key_sample(sample);
      const bool queued = u.queue().size() > 0;
      u.main_loop();
      coils.feed(u.port());  // a drive change at rest moves the coils without a step
      if (queued && !pressed) {
        pressed = true;
        if (known_key >= 0) m.press(known_key, running);
        check_display();
      }
    }
    require(pressed);  // a press held 20 ms past its bounce always counts
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Rig r;
  for (std::size_t i = 0; i < size && i < 400; ++i) {
    const std::uint8_t op = data[i];
    if (op < 0xA0) {
      const bool unused = op >= 0x50 && op < 0x60;
      const int k = op % 5;
      r.key(unused ? kUnused[op % 4] : kCodes[k], unused ? -1 : k, 26 + (op >> 3) % 26);
    } else {
      const int periods = (op - 0x9F) * 16;
      for (int s = 0; s < periods; ++s) {
        r.step();
        r.u.main_loop();
      }
      r.check_display();
    }
  }
  return 0;
}
