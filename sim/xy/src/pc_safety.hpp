// The axis safety properties the simulated PC checks on the telemetry, every step and board
// (docs/sim.md "Safety properties on the telemetry"). An observer of the link to the board: the
// jog-watchdog property needs to know when a valid frame last reached the board, and parsing
// the frames for that here keeps it off the path that moves them.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "pc/dds/bus.hpp"
#include "sim/xy/fault_link.hpp"

namespace ap::sim::xy {

struct PcContext;
struct BoardPc;

class SafetyCheck : public LinkObserver {
 public:
  // The bytes that left the link for the board at t.
  void left(std::int64_t t, std::span<const std::uint8_t> bytes, std::span<const FrameTag> tags) override;
  // A new telemetry sample; `before` the last one (none at the first).
  void sampled(const dds::Telemetry* before, const dds::Telemetry& now);
  // The properties on the board's last sample and the one before it.
  void check(PcContext& pc, const BoardPc& b, std::int64_t t) const;

 private:
  // The sample before the last change, per axis (none before the second sample).
  std::array<dds::AxisTelemetry, 2> prev_{};
  std::array<bool, 2> have_prev_{};
  bool session_ = true;                 // the last sample's BLE pins: a data session (or none yet)
  std::int64_t last_delivered_us_ = 0;  // a valid frame last reached the board in a session
};

}  // namespace ap::sim::xy
