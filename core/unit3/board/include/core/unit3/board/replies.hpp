#pragma once
// The unit's transmit queue (docs/unit3.md "Replies"): whole replies or nothing. The UART
// sends 1920 bytes/s at 19200 8N1 [T]; a reply that does not fit in the queue is dropped
// whole and counted, never sent in part, so the PC never reads half a report.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace ap::unit3_board {

class Replies {
 public:
  static constexpr std::size_t kCapacity = 256;  // [D]: four full reports of the three axes
  // Queues `bytes` whole; false (and counted) when they do not fit.
  bool put(std::span<const std::uint8_t> bytes);
  // Moves up to out.size() queued bytes into out, oldest first; returns how many.
  std::size_t take(std::span<std::uint8_t> out);
  std::size_t size() const { return size_; }
  std::uint32_t dropped() const { return dropped_; }

 private:
  std::array<std::uint8_t, kCapacity> buf_{};
  std::size_t head_ = 0;  // the oldest byte
  std::size_t size_ = 0;
  std::uint32_t dropped_ = 0;
};

}  // namespace ap::unit3_board
