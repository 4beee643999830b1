// The delivery check of the simulated PC (docs/sim.md "Delivery check"): exactly once and in
// order, stop first, a confirmed stop stops, and every outcome the client reports against what
// the board did with its frame. Its own object so that the accounting is told what the client
// took and answered (submitted, echo) instead of being worked out inline on the transport path.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "pc/xy/client/client.hpp"
#include "sim/xy/digest.hpp"

namespace ap::sim::xy {

struct PcContext;
struct BoardPc;

class DeliveryCheck {
 public:
  // The client took command `c` at t as ticket `tk`; `next_seq` is the seq its next new frame takes.
  void submitted(const xy_client::Command& c, xy_client::Ticket tk, std::uint16_t next_seq, std::int64_t t);
  // An echo the client told apart: an answer counts its frame (and closes a gap).
  void echo(const xy_client::EchoEvent& ev);
  // After the echoes of a step: the gaps, the commands that settled, the stops confirmed.
  void settle(PcContext& pc, BoardPc& b, std::int64_t t);
  // At the end: the frames the board took against the frames the client saw answered.
  void finish(PcContext& pc, BoardPc& b, std::int64_t t);

  [[nodiscard]] std::uint64_t frames_answered() const { return answered_frames_; }
  // Every settled command, in settling order.
  [[nodiscard]] const std::vector<xy_client::Report>& reports() const { return reports_; }

 private:
  void check_outcome(PcContext& pc, BoardPc& b, const xy_client::Report& r, std::int64_t t);

  // The stop check: a confirmed stop must bring the axis to rest within the ramp time, unless
  // a later command for the axis was issued.
  struct Axis {
    std::optional<std::int64_t> stop_deadline_us;
    std::int64_t stop_issued_us = 0;
    std::optional<std::int64_t> last_motion_issue_us;
  };
  std::array<Axis, 2> ax_{};
  // Every frame the client saw answered (their digest, as the board's `probe taken`), the
  // settled commands, and the seq each stop had to go out with.
  std::uint64_t answered_frames_ = 0;
  std::uint64_t answered_digest_ = kFnvBasis;
  std::vector<xy_client::Report> reports_;
  std::map<xy_client::Ticket, std::uint16_t> stop_seq_;
  std::uint32_t timeouts_seen_ = 0;
  bool gap_open_ = false;
  std::uint32_t outcome_failures_ = 0;
};

}  // namespace ap::sim::xy
