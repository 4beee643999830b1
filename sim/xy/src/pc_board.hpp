// What the simulated PC keeps for the whole run and for each board (docs/sim.md "The simulated
// PC"). Its jobs are one file each (actions, driving the client, the delivery, echo and safety
// checks, expectations, the report); this is what they share: the scenario, the mechanics the
// PC assumes, the one list of failures in the order they were found (the report prints them so),
// and per board its endpoint, client, links, last telemetry and each check's own state.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pc/dds/bus.hpp"
#include "pc/xy/client/client.hpp"
#include "protocol/xy/codec/subscribers.hpp"
#include "sim/xy/fault_link.hpp"
#include "sim/xy/scenario.hpp"
#include "sim/xy/verdict.hpp"
#include "pc_delivery.hpp"
#include "pc_echoes.hpp"
#include "pc_expectations.hpp"
#include "pc_safety.hpp"

namespace ap::sim::xy {

// Mechanics the PC assumes (defaults, setup, and the speeds and accelerations it set since):
// the units of the telemetry and the bounds of the checks.
struct PcMech {
  double um_per_ustep = 2000.0 / 3200.0;
  double fast_um_s = 10'000, slow_um_s = 2000, start_um_s = 500, accel_um_s2 = 20'000, home_um_s = 2000;
  double max_speed_um_s = 10'000;   // the highest speed limit ever requested
  double min_accel_um_s2 = 20'000;
};

struct PcContext {
  PcContext(const scenario::Scenario& scn, const RunOptions& options) : s(scn), opt(options) {}
  void fail(const std::string& m) {
    if (failures.size() < 200) failures.push_back(m);
  }

  const scenario::Scenario& s;
  const RunOptions& opt;
  PcMech mech;
  // What the subscriber slots of every new frame request: the scenario's subscriptions, and the
  // parameters its param.NAME expectations read (slot 3, one per new frame in turn).
  std::vector<xy_codec::SubscriberId> subscribed;
  std::vector<std::uint8_t> param_slots;
  std::uint64_t round_trips = 0;
  std::vector<std::string> failures;
};

// What the PC's user holds on one axis.
struct HeldKey {
  std::int32_t jog = 0;          // held jog level (sign = direction), 0 = none
  bool jogging = false;          // the last motion command of this axis is a jog
};

struct BoardPc {
  BoardPc(PcContext& pc, const dds::ParticipantPtr& pp, std::uint32_t board);   // pc_transport.cpp

  std::uint32_t id = 0;
  BoardVerdict verdict;
  std::array<HeldKey, 2> keys{};
  dds::Telemetry tel{};
  bool have_tel = false;
  // The checks first: the links hold them as observers.
  DeliveryCheck delivery;
  EchoCheck echoes;
  SafetyCheck safety;
  EchoReadings seen;
  std::unique_ptr<dds::PcEndpoint> ep;
  std::unique_ptr<xy_client::Client> client;
  std::unique_ptr<FaultLink> down, up;   // to the board, to the PC
  std::uint64_t cmd_seq = 0;             // the bus command of this step, whose echo is awaited
};

using Boards = std::vector<std::unique_ptr<BoardPc>>;

}  // namespace ap::sim::xy
