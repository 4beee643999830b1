// Test fixture for the board core: the core wired to the TMC2130 and MB85RS256B device
// models and, on one simulated I2C bus, the TMP117 and ICM-20789 models; scripted inputs,
// captured UART echoes and motor outputs. Shared by the board tests
// and the board fuzz target (fuzz/xy/board), so both drive the board exactly the same way.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/board/board.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "models/xy/fram/mb85rs256b.hpp"
#include "models/xy/i2c/bus.hpp"
#include "models/xy/icm20789/device.hpp"
#include "models/xy/tmc2130/device.hpp"
#include "models/xy/tmp117/device.hpp"

namespace ap::xy_board::test {

using Echo = std::array<std::uint8_t, xy_codec::kEchoLength>;

// A part on the sensor bus that can be taken off it: absent, it acknowledges nothing
// (AddressNack), as an unpowered chip or a broken trace does.
template <class D>
struct Plug : model::xy_i2c::Device {
  D chip{};
  bool present = true;
  xy_i2c::Status transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) override {
    return present ? chip.transfer(address, tx, rx) : xy_i2c::Status::AddressNack;
  }
};

struct Rig {
  model::Mb85rs256b fram;
  std::array<model::xy_tmc2130::Device, kAxes> tmc{};
  Plug<model::xy_tmp117::Device> tmp117{};
  Plug<model::xy_icm20789::Device> gyro{};
  model::xy_i2c::Bus i2c{};
  // Every transaction on the bus fails like this (a stuck bus), until healed; nullopt: none.
  std::optional<xy_i2c::Status> bus_fault;
  Inputs in{};
  std::vector<Echo> tx;  // every echo the board sent, in order
  std::array<MotorOutput, kAxes> motor{};
  std::array<std::int64_t, kAxes> steps_total{};  // STEP edges the core sent, signed by DIR
  // How far each motor turned, in 1/256 full step, as the TMC2130 model lets it: nothing
  // while the power stage is off (TOFF = 0 or DRV_ENN high), CHOPCONF.MRES per edge.
  std::array<std::int64_t, kAxes> rotor_256{};
  int kill_switch_pulls = 0;  // Hardware::power_off calls
  std::vector<bool> charger_enables;  // Hardware::charger_enable calls, in order
  std::unique_ptr<Board> board;
  std::uint16_t seq = 0;

  Rig() {
    i2c.attach(tmp117);
    i2c.attach(gyro);
    in.ble_status1 = false;  // Data Session open (Tab. 7-2: 0, 1)
    in.ble_status2 = true;
    in.battery_mv = 4000;
  }

  static void sample(void* ctx, Inputs& out) { out = static_cast<Rig*>(ctx)->in; }
  static void drive(void* ctx, Axis a, const MotorOutput& m) {
    auto* r = static_cast<Rig*>(ctx);
    r->motor[static_cast<std::size_t>(a)] = m;
    const auto i = static_cast<std::size_t>(a);
    r->steps_total[i] += m.dir * static_cast<std::int64_t>(m.steps);
    r->tmc[i].set_drv_enn(!m.enable);
    r->rotor_256[i] += r->tmc[i].step(m.steps, m.dir);
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

  Hardware hardware() {
    Hardware hw;
    hw.ctx = this;
    hw.tmc = {tmc[0].port(), tmc[1].port()};
    hw.fram = fram.bus();
    hw.i2c = i2c.port();
    hw.sample = &Rig::sample;
    hw.motor = &Rig::drive;
    hw.uart_tx = &Rig::uart;
    hw.power_off = &Rig::kill;
    hw.charger_enable = &Rig::charger;
    return hw;
  }

  // Power-up (or reboot: the FRAM and the driver chips keep their contents).
  BootResult boot() {
    board = std::make_unique<Board>(hardware());
    return board->boot();
  }

  // One 1 ms tick: the TMP117's conversions run on the same clock as the board.
  void tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      tmp117.chip.advance_ms(1);
      for (auto& d : tmc) d.elapse_us(1000);
      board->tick();
      for (auto& d : tmc) d.clear_log();
      i2c.clear_log();
    }
  }

  // A stuck bus (every transaction fails with `s`) or a healed one.
  void fail_bus(xy_i2c::Status s) {
    bus_fault = s;
    i2c.fail_at(0, s, true);
  }
  void heal_bus() {
    bus_fault.reset();
    i2c.heal();
  }
  // How every transaction to each sensor ends now.
  xy_i2c::Status tmp117_answers() const { return bus_fault ? *bus_fault : (tmp117.present ? xy_i2c::Status::Ok : xy_i2c::Status::AddressNack); }
  xy_i2c::Status gyro_answers() const { return bus_fault ? *bus_fault : (gyro.present ? xy_i2c::Status::Ok : xy_i2c::Status::AddressNack); }

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

  const xy_axis::State& ax(Axis a) const { return board->axis_state(a); }
};

}  // namespace ap::xy_board::test
