// The delivery check of the simulated PC (pc_delivery.hpp, docs/sim.md "Delivery check"): the
// exactly-once accounting apart from the path it accounts for, so neither changes the other unseen.
#include "pc_delivery.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "sim/text.hpp"
#include "sim/xy/outcome_oracle.hpp"
#include "pc_board.hpp"
#include "pc_transport.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;
using xy_codec::CommandId;

void DeliveryCheck::submitted(const xy_client::Command& c, xy_client::Ticket tk, std::uint16_t next_seq, std::int64_t t) {
  // A stop must leave in the next new frame (docs/protocol.md "Delivery"): behind at most
  // the frame already in flight, never behind anything queued.
  if (c.cmd.id == CommandId::Stop && c.part != xy_client::Part::Unit) stop_seq_[tk] = next_seq;
  if (c.part != xy_client::Part::Unit) {
    Axis& x = ax_[c.part == xy_client::Part::Y ? 1 : 0];
    if (c.cmd.id != CommandId::Stop) x.last_motion_issue_us = t;
  }
}

void DeliveryCheck::echo(const xy_client::EchoEvent& ev) {
  if (ev.kind != xy_client::EchoKind::Answer) return;
  ++answered_frames_;
  gap_open_ = false;
  if (const auto bytes = xy_client::format(ev.answered)) {
    answered_digest_ = fnv1a(answered_digest_, std::span<const std::uint8_t>(
                                                   reinterpret_cast<const std::uint8_t*>(bytes->data()), bytes->size()));
  }
}

void DeliveryCheck::settle(PcContext& pc, BoardPc& b, std::int64_t t) {
  // A gap is a run of retransmission timeouts with no answer in between.
  const std::uint32_t timeouts = b.client->counters().timeouts;
  if (timeouts > timeouts_seen_) {
    if (gap_open_ && !b.verdict.gaps.empty()) {
      b.verdict.gaps.back().lost += timeouts - timeouts_seen_;
    } else {
      b.verdict.gaps.push_back({t, timeouts - timeouts_seen_});
    }
    gap_open_ = true;
  }
  timeouts_seen_ = timeouts;
  const double stop_s = pc.mech.max_speed_um_s / std::max(1.0, pc.mech.min_accel_um_s2);
  for (xy_client::Report& r : b.client->take_reports()) {
    const auto it = stop_seq_.find(r.ticket);
    if (it != stop_seq_.end()) {
      const std::size_t i = r.command.part == xy_client::Part::Y ? 1 : 0;
      if (r.seq && *r.seq != it->second && b.client->counters().resyncs == 0) {
        pc.fail("delivery: board " + std::to_string(b.id) + ": the stop of axis " + (i == 0 ? "x" : "y") + " issued at " +
                tstr(r.issued_us) + " went out in frame " + std::to_string(*r.seq) + ", not in the next new frame (" +
                std::to_string(it->second) + ")");
      }
      if (r.outcome == xy_client::Outcome::Done) {
        ax_[i].stop_deadline_us = t + static_cast<std::int64_t>(stop_s * 1e6) + 2 * pc.opt.step_us;
        ax_[i].stop_issued_us = r.issued_us;
      }
      stop_seq_.erase(it);
    }
    check_outcome(pc, b, r, t);
    reports_.push_back(r);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    Axis& x = ax_[i];
    if (!x.stop_deadline_us || t < *x.stop_deadline_us) continue;
    const bool later_command = x.last_motion_issue_us && *x.last_motion_issue_us >= x.stop_issued_us;
    if (!later_command && b.tel.axis[i].speed != 0) {
      pc.fail("delivery: board " + std::to_string(b.id) + " axis " + (i == 0 ? "x" : "y") + " still moves at " + tstr(t) +
              ", a ramp time after its stop was confirmed");
    }
    x.stop_deadline_us.reset();
  }
}

// The outcome check (docs/sim.md "Outcome check"): the outcome the user is told against what
// the board did with the frame, as the board-side echo model states it. A disagreement fails
// the run like a safety violation.
void DeliveryCheck::check_outcome(PcContext& pc, BoardPc& b, const xy_client::Report& r, std::int64_t t) {
  std::optional<model::xy_echo::FrameFate> fate;
  if (xy_client::delivered(r.outcome) && r.seq) {  // done, refused, blocked: a frame answered it
    const std::string text = env(pc, b, "probe fate." + std::to_string(*r.seq), t);
    if (text != "none") {
      fate = parse_fate(text);
      if (!fate) {
        pc.fail("outcome: board " + std::to_string(b.id) + ": unreadable fate '" + text + "'");
        return;
      }
    }
  }
  ++b.verdict.delivery.outcomes_checked;
  if (const auto m = ap::sim::xy::check_outcome(r, fate)) {
    if (++outcome_failures_ <= 5) pc.fail("outcome: board " + std::to_string(b.id) + " at " + tstr(t) + ": " + *m);
  }
}

// Exactly once, in order: the frames the board took are the frames the client saw answered, one
// for one and in the same order, unless a frame ran out of transmissions (its fate is unknown:
// at most once) or a raw frame went around the client.
void DeliveryCheck::finish(PcContext& pc, BoardPc& b, std::int64_t t) {
  const std::string who = "delivery: board " + std::to_string(b.id);
  const xy_client::ClientCounters& c = b.client->counters();
  BoardVerdict& v = b.verdict;
  std::istringstream in(env(pc, b, "probe taken", t));
  std::uint64_t taken = 0, digest = 0;
  if (!(in >> taken >> digest)) {
    pc.fail(who + ": no answer to probe taken");
    return;
  }
  v.delivery.frames_taken = taken;
  const bool raw = std::any_of(pc.s.actions.begin(), pc.s.actions.end(), [](const sc::Action& a) { return a.verb == sc::Verb::raw; });
  if (raw) return;
  // The frame in flight at the end may have been taken without its answer arriving yet.
  const std::uint64_t open = b.client->in_flight_seq() ? 1U : 0U;
  if (c.given_up == 0 && open == 0) {
    if (taken != answered_frames_ || digest != answered_digest_) {
      pc.fail(who + ": the board took " + std::to_string(taken) + " frames, the client saw " +
              std::to_string(answered_frames_) + " answered" + (digest != answered_digest_ ? " (not the same frames)" : ""));
    }
  } else if (taken < answered_frames_ || taken > answered_frames_ + c.given_up + open) {
    pc.fail(who + ": the board took " + std::to_string(taken) + " frames; the client saw " + std::to_string(answered_frames_) +
            " answered, gave up " + std::to_string(c.given_up) + " and has " + std::to_string(open) + " in flight");
  }
}

}  // namespace ap::sim::xy
