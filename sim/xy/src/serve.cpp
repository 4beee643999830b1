// The board side of a run (docs/sim.md "The bus protocol of a run"): one SimBoard behind one
// bus endpoint, answering every bus command with one echo.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>
#include <vector>

#include "sim/xy/board.hpp"
#include "sim/xy/run.hpp"
#include "sim/serve_loop.hpp"

namespace ap::sim::xy {

dds::Telemetry telemetry_of(SimBoard& sb, std::uint32_t id) {
  dds::Telemetry t;
  t.board = id;
  t.vtime_us = static_cast<std::uint64_t>(sb.now_us());
  if (!sb.booted()) return t;
  const xy_board::Board& b = sb.core();
  t.main_state = static_cast<std::uint8_t>(b.main_state());
  const xy_board::Inputs& in = b.inputs();
  t.ble_status = static_cast<std::uint8_t>((in.ble_status1 ? 1U : 0U) | (in.ble_status2 ? 2U : 0U));
  t.led = sb.led();
  t.charger = in.charger;
  t.usb = in.usb;
  t.low_battery = b.block() == xy_board::Block::Battery;
  t.battery_mv = in.battery_mv;
  t.charge_ma = static_cast<std::int16_t>(std::clamp(in.charge_ma, -32768, 32767));
  t.temperature_mc = b.temperature_mc();
  t.rotation_mdeg = b.rotation_mdeg();
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    const auto ax = static_cast<xy_board::Axis>(a);
    const xy_axis::State& s = b.axis_state(ax);
    dds::AxisTelemetry& o = t.axis[a];
    o.pos = s.pos;
    o.target = s.target;
    o.speed = s.v / xy_axis::kSpeedScale;
    o.dir = s.dir > 0 ? 1 : 0;
    o.state = static_cast<std::uint8_t>(s.phase);
    o.endstop_min = in.endstop_min[a] != 0;
    o.endstop_max = in.endstop_max[a] != 0;
    o.blocked = b.block() != xy_board::Block::None;
    o.enabled = b.motor_output(ax).enable;
  }
  return t;
}

int serve_board(const dds::ParticipantPtr& participant, const BoardOptions& opt, std::chrono::milliseconds idle_timeout,
                const std::atomic<bool>* stop) {
  dds::BoardEndpoint ep(participant, opt.id);
  SimBoard board(opt);
  return serve_loop(
      ep, board, idle_timeout, stop,
      [&](const dds::CommandSample& cmd) {
        board.advance_to(static_cast<std::int64_t>(cmd.vtime_us));
        if (!cmd.bytes.empty()) board.rx(cmd.bytes);
        return board.take_tx(dds::kFrameMax);
      },
      [&] { return telemetry_of(board, opt.id); });
}

}  // namespace ap::sim::xy
