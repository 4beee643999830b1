// The scenario's expectations, checked by the simulated PC (docs/sim.md "Expectations"): when
// each is due, the value of its subject (telemetry, echoes, the client's counters and reports,
// probes of the board's models) and the failure it reports. The echoes' part of those values
// is kept by EchoReadings, which the transport hands every echo the client told apart.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "protocol/xy/codec/statuses.hpp"
#include "sim/xy/scenario.hpp"

namespace ap::sim::xy {

struct PcContext;
struct BoardPc;

// What the echoes of one board told the PC: the subjects x.status, sub.NAME, param.NAME, echo.*.
struct EchoReadings {
  void echo(const xy_client::EchoEvent& ev);

  struct Axis {
    xy_codec::EchoStatus status = xy_codec::EchoStatus::Idle;
    bool have_status = false;
    std::int32_t data = 0;
  };
  std::array<Axis, 2> ax{};
  std::map<std::string, std::int32_t> subs;      // subscriber key -> latest data
  std::map<std::uint8_t, std::int32_t> params;   // param index -> latest data
  std::uint32_t echoes = 0;
};

// The parameters the echoes must carry for the scenario's param.NAME expectations (their
// indices, each once); throws std::runtime_error on an unknown name.
std::vector<std::uint8_t> expected_params(const scenario::Scenario& s);

class Expectations {
 public:
  explicit Expectations(PcContext& pc);
  // Every expectation of board `b` due at step t (at_end: after the last step).
  void evaluate(BoardPc& b, std::int64_t t, bool at_end);

 private:
  std::string describe(const scenario::Expectation& e, std::uint32_t board) const;

  PcContext& pc_;
  std::vector<std::vector<bool>> done_;   // per board and expectation: settled
  std::map<std::size_t, std::string> last_;   // per expectation: the last value shown
};

}  // namespace ap::sim::xy
