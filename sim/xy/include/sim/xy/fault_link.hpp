// The fault injector of the simulated link (docs/sim.md "Fault injection"): per direction and
// frame, with the scenario's seed, drop / corrupt / duplicate / reorder / delay within their
// time windows, and `link cut`; it counts what it did in LinkStats and tags each frame with it
// (the PC's echo check). The link only moves bytes: whoever checks what it carried is its
// LinkObserver, called with the bytes and tags that leave it.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "sim/xy/scenario.hpp"
#include "sim/xy/verdict.hpp"

namespace ap::sim::xy {

using Bytes = std::vector<std::uint8_t>;

// What the link did to one frame, carried with it (the PC's echo check, docs/sim.md "Echo
// checks"): `index` is the frame's number in the order frames entered the link (on the link to
// the PC every echo the bus brought enters it, so it is the board's echo number), the rest is
// the injector's own record.
struct FrameTag {
  std::uint64_t index = 0;
  std::uint32_t corruptions = 0;   // bytes XORed on purpose
  bool duplicate = false;          // the second copy of a duplicated frame
  bool reordered = false;          // held and sent after the next frame
};

// Checks what a link carried (docs/sim.md "Echo checks", "Safety properties on the
// telemetry"): called by the link, so parsing and accounting stay off the path that moves the
// bytes between the client and the bus.
class LinkObserver {
 public:
  virtual ~LinkObserver() = default;
  // Every pop(): the bytes that left the link at t (possibly none) and the tag of each frame in
  // them, in order.
  virtual void left(std::int64_t t, std::span<const std::uint8_t> bytes, std::span<const FrameTag> tags) = 0;
};

class FaultLink {
 public:
  // `observer` (optional) must outlive the link.
  FaultLink(const std::vector<scenario::Fault>& faults, scenario::Direction dir, std::uint64_t seed,
            LinkObserver* observer = nullptr);
  void cut_until(std::int64_t t) { cut_until_ = t; }
  [[nodiscard]] bool cut(std::int64_t t) const { return t < cut_until_; }

  // One frame entering the link at t.
  void push(std::int64_t t, Bytes frame, LinkStats& st);

  // Frames still inside the link (queued or held).
  [[nodiscard]] std::size_t in_flight() const { return queue_.size() + (held_ ? 1U : 0U); }

  // Frames that leave the link by t, in order, at most max_bytes (the rest wait); the observer
  // sees them with their tags.
  Bytes pop(std::int64_t t, std::size_t max_bytes, LinkStats& st);

 private:
  bool roll(double p);
  std::vector<scenario::Fault> faults_;
  LinkObserver* observer_;
  std::uint64_t entered_ = 0;   // frames pushed so far: the next frame's index
  struct Held {
    std::int64_t at;
    Bytes bytes;
    FrameTag tag;
  };
  std::mt19937_64 rng_;
  std::deque<Held> queue_;
  std::optional<Held> held_;
  std::int64_t cut_until_ = -1;
};

}  // namespace ap::sim::xy
