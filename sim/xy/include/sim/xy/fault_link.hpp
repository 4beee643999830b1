// The fault injector of the simulated link (docs/sim.md "Fault injection"): per direction and
// frame, with the scenario's seed, drop / corrupt / duplicate / reorder / delay within their
// time windows, and `link cut`; it counts what it did in LinkStats and tags each frame with it
// (the PC's echo check).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <vector>

#include "sim/xy/scenario.hpp"
#include "sim/xy/run.hpp"

namespace ap::sim::xy {

using Bytes = std::vector<std::uint8_t>;

// What the link did to one frame, carried with it (the PC's echo check, docs/sim.md "Echo
// checks"): `index` is given by the PC when the frame enters the link (the board's echo number),
// the rest is the injector's own record.
struct FrameTag {
  std::uint64_t index = 0;
  std::uint32_t corruptions = 0;   // bytes XORed on purpose
  bool duplicate = false;          // the second copy of a duplicated frame
  bool reordered = false;          // held and sent after the next frame
};

class FaultLink {
 public:
  FaultLink(const std::vector<scenario::Fault>& faults, scenario::Direction dir, std::uint64_t seed);
  void cut_until(std::int64_t t) { cut_until_ = t; }
  [[nodiscard]] bool cut(std::int64_t t) const { return t < cut_until_; }

  // One frame entering the link at t.
  void push(std::int64_t t, Bytes frame, LinkStats& st, std::uint64_t index = 0);

  // Frames still inside the link (queued or held).
  [[nodiscard]] std::size_t in_flight() const { return queue_.size() + (held_ ? 1U : 0U); }

  // Frames that leave the link by t, in order, at most max_bytes (the rest wait).
  // `tags` (optional) receives the tag of each delivered frame, in order.
  Bytes pop(std::int64_t t, std::size_t max_bytes, LinkStats& st, std::vector<FrameTag>* tags = nullptr);

 private:
  bool roll(double p);
  std::vector<scenario::Fault> faults_;
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
