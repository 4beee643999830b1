// The unit's firmware (core/unit3/board) driven by bytes, the stick, endstops, buttons, time
// and power cycles (docs/unit3.md "The board"). The input is a list of operations:
//   0x00-0x9F  one byte to the UART (the byte itself, 0x00-0x7F, or the next input byte)
//   0xA0-0xAF  the stick of axis (op & 3) % 3 to the next two bytes (little end first)
//   0xB0-0xBF  the endstop inputs to the next byte
//   0xC0-0xCF  button (op & 0xF) % 6
//   0xD0-0xEF  (op & 0x1F) + 1 ms, times 16 when the next byte is odd
//   0xF0-0xFF  power cycle
// Oracles: no crash or UB; every reply is exactly what the reference model of the PC's view
// (models/unit3) says; no pulse towards a closed endstop or against a PC move, no stick start
// outside the POSITIONS window; a running axis changes direction only from ramp entry 0 and
// moves one entry at a time; counters stay in the 18-digit range.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/unit3/board/unit.hpp"
#include "models/unit3/pc_view.hpp"
#include "sim/unit3/replies.hpp"

namespace {

namespace u = ap::unit3_board;
using ap::model::unit3::PcView;

void require(bool ok) {
  if (!ok) std::abort();
}

std::vector<std::string> split(const std::string& rx) {
  std::string rest;
  const auto v = ap::sim::unit3::split_replies(rx, &rest);
  require(rest.empty());  // replies are whole or absent
  return v;
}

struct Rig {
  std::array<std::uint8_t, 8> eeprom{};
  std::unique_ptr<u::Unit> unit;
  PcView model;
  u::Inputs in{};
  std::uint8_t seen = 0;
  std::array<int, 3> entry{}, dir{1, 1, 1};
  std::array<bool, 3> running{};

  Rig() {
    eeprom.fill(0xFF);
    unit = std::make_unique<u::Unit>(eeprom);
  }
  std::string take() { return ap::sim::unit3::take_all(*unit); }
  void byte(std::uint8_t b) {
    unit->receive(b);
    require(split(take()) == model.receive(std::string(1, static_cast<char>(b)), seen));
  }
  void press(int b) {
    unit->press(static_cast<ap::unit3_menu::Button>(b));
    require(split(take()) == model.press(b));
  }
  void tick() {
    unit->tick(in);
    seen = in.endstops;
    ap::model::unit3::Pins p;
    for (std::size_t a = 0; a < 3; ++a) {
      const auto& o = unit->out(a);
      const int e = unit->axis(a).entry;
      p.pulses[a] = o.pulses;
      p.dir[a] = o.dir;
      p.running[a] = o.running;
      if (running[a] && o.running) {
        require(e - entry[a] <= 1 && entry[a] - e <= 1);
        require(o.dir == dir[a] || entry[a] == 0);
      }
      require(unit->axis(a).counter <= 999'999'999'999'999'999LL && unit->axis(a).counter >= -999'999'999'999'999'999LL);
      entry[a] = e;
      dir[a] = o.dir;
      running[a] = o.running;
    }
    std::vector<int> stopped, cut;
    std::string why;
    require(model.tick(p, in.endstops, stopped, cut, why));
    std::size_t e23 = 0;
    for (const auto& r : split(take())) {
      if (r == "E23;") {
        ++e23;
        continue;
      }
      require(r.size() == 21 && r[0] >= 'X' && r[0] <= 'Z');
      require(r == PcView::report(r[0] - 'X', model.counter(r[0] - 'X')));
    }
    require(e23 == cut.size());
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Rig r;
  std::size_t i = 0;
  const auto next = [&]() -> std::uint8_t { return i < size ? data[i++] : 0; };
  std::uint32_t budget = 200'000;  // ms of simulated time per input, so every input ends fast
  while (i < size) {
    const std::uint8_t op = data[i++];
    if (op < 0x80) {
      r.byte(op);
    } else if (op < 0xA0) {
      r.byte(next());
    } else if (op < 0xB0) {
      const std::uint16_t lo = next();
      const auto v = static_cast<std::uint16_t>(lo | static_cast<std::uint16_t>(next() << 8));
      r.in.adc[(op & 3U) % 3U] = v;
    } else if (op < 0xC0) {
      r.in.endstops = next();
    } else if (op < 0xD0) {
      r.press((op & 0xF) % 6);
    } else if (op < 0xF0) {
      std::uint32_t ms = (op & 0x1FU) + 1U;
      if ((next() & 1U) != 0) ms *= 16U;
      for (std::uint32_t t = 0; t < ms && budget > 0; ++t, --budget) r.tick();
    } else {
      r.unit = std::make_unique<u::Unit>(r.eeprom);
      r.model.power_cycle();
      r.seen = 0;
      r.running = {};
    }
  }
  return 0;
}
