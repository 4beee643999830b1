// The board core (core/xy/board) on the board's device models (sim/xy/rig/parts.hpp), driven
// by a script: inputs set by the caller, every UART echo and motor output captured. The board
// tests (properties/xy/board, properties/xy/path) and the board fuzz target (fuzz/xy/board)
// share it, so all of them drive the board exactly the same way (docs/board.md "Verification").
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/xy/board/board.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/xy/rig/parts.hpp"

namespace ap::sim::xy {

struct Rig : BoardParts {
  using Echo = std::array<std::uint8_t, xy_codec::kEchoLength>;

  xy_board::Inputs in{};
  std::vector<Echo> tx;  // every echo the board sent, in order
  std::array<xy_board::MotorOutput, xy_board::kAxes> motor{};
  std::array<std::int64_t, xy_board::kAxes> steps_total{};  // STEP edges the core sent, signed by DIR
  // How far each motor turned, in 1/256 full step, as the TMC2130 model lets it: nothing
  // while the power stage is off (TOFF = 0 or DRV_ENN high), CHOPCONF.MRES per edge.
  std::array<std::int64_t, xy_board::kAxes> rotor_256{};
  int kill_switch_pulls = 0;  // Hardware::power_off calls
  std::vector<bool> charger_enables;  // Hardware::charger_enable calls, in order
  std::unique_ptr<xy_board::Board> board;
  std::uint16_t seq = 0;

  Rig() {
    in.ble_status1 = false;  // Data Session open (Tab. 7-2: 0, 1)
    in.ble_status2 = true;
    in.battery_mv = 4000;
  }

  static void sample(void* ctx, xy_board::Inputs& out) { out = static_cast<Rig*>(ctx)->in; }
  static void drive(void* ctx, xy_board::Axis a, const xy_board::MotorOutput& m) {
    auto* r = static_cast<Rig*>(ctx);
    const auto i = static_cast<std::size_t>(a);
    r->motor[i] = m;
    r->steps_total[i] += m.dir * static_cast<std::int64_t>(m.steps);
    r->rotor_256[i] += r->turn(i, m.enable, m.steps, m.dir);
  }
  static void kill(void* ctx) { ++static_cast<Rig*>(ctx)->kill_switch_pulls; }
  static void charger(void* ctx, bool on) { static_cast<Rig*>(ctx)->charger_enables.push_back(on); }
  static void uart(void* ctx, std::span<const std::uint8_t> bytes) {
    Echo e{};
    if (bytes.size() == e.size()) {
      std::copy(bytes.begin(), bytes.end(), e.begin());
      static_cast<Rig*>(ctx)->tx.push_back(e);
    }
  }

  xy_board::Hardware hardware() {
    xy_board::Hardware hw;
    hw.ctx = this;
    wire(hw);
    hw.sample = &Rig::sample;
    hw.motor = &Rig::drive;
    hw.uart_tx = &Rig::uart;
    hw.power_off = &Rig::kill;
    hw.charger_enable = &Rig::charger;
    return hw;
  }

  // Power-up (or reboot: the FRAM and the driver chips keep their contents).
  xy_board::BootResult boot() {
    board = std::make_unique<xy_board::Board>(hardware());
    return board->boot();
  }

  // One 1 ms tick: the TMP117's conversions and the drivers' clocks run on the board's.
  void tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      tmp117.chip.advance_ms(1);
      drivers_tick();
      board->tick();
      clear_logs();
    }
  }

  static xy_frame::CommandFrame frame_of(std::uint16_t s, xy_codec::CommandId x, std::int32_t xd, xy_codec::CommandId y,
                                         std::int32_t yd, xy_frame::SubscriberSlots subs = {}) {
    xy_frame::CommandFrame f;
    f.seq = static_cast<std::uint16_t>(s % xy_codec::kSeqModulo);
    f.x = {x, xd};
    f.y = {y, yd};
    f.subs = subs;
    return f;
  }

  static std::array<std::uint8_t, xy_codec::kCommandLength> bytes_of(const xy_frame::CommandFrame& f) {
    std::array<std::uint8_t, xy_codec::kCommandLength> b{};
    (void)xy_frame::format_command(f, b);
    return b;
  }

  // Sends one command frame (next sequence number) into the UART.
  void send(xy_codec::CommandId x, std::int32_t xd, xy_codec::CommandId y = xy_codec::CommandId::Nop, std::int32_t yd = 0,
            xy_frame::SubscriberSlots subs = {}) {
    const auto b = bytes_of(frame_of(++seq, x, xd, y, yd, subs));
    board->uart_rx(b);
  }
  void send_raw(std::span<const std::uint8_t> b) { board->uart_rx(b); }

  std::optional<xy_frame::EchoFrame> last_echo() const {
    if (tx.empty()) return std::nullopt;
    xy_frame::EchoFrame e;
    if (!xy_frame::parse_echo(tx.back(), e).ok()) return std::nullopt;
    return e;
  }

  const xy_axis::State& ax(xy_board::Axis a) const { return board->axis_state(a); }
};

}  // namespace ap::sim::xy
