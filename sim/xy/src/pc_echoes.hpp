// The echo checks of the simulated PC (docs/sim.md "Echo checks"): the echoes the bus brought
// are the board's TX stream, the echoes that reached the client are ones the board sent, intact
// unless the link says it damaged them, and in order; at the end also the board-side echo
// model's findings. An observer of the link to the PC, so that the transport only moves the
// echoes and the accounting of each one happens here.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sim/xy/digest.hpp"
#include "sim/xy/fault_link.hpp"

namespace ap::sim::xy {

struct PcContext;
struct BoardPc;

class EchoCheck : public LinkObserver {
 public:
  EchoCheck(PcContext& pc, std::uint32_t board) : pc_(pc), board_(board) {}
  // The TX bytes the bus brought from the board at t, before their echoes enter the link.
  void brought(std::int64_t t, std::span<const std::uint8_t> bytes);
  // The echoes that left the link for the client.
  void left(std::int64_t t, std::span<const std::uint8_t> bytes, std::span<const FrameTag> tags) override;
  // At the end (probes of the board): the echo model's findings, the board's TX stream against
  // what the bus brought, and the echoes that never arrived against what the link lost.
  void finish(BoardPc& b, std::int64_t t);

 private:
  void bad(std::int64_t t, const std::string& what);

  PcContext& pc_;
  std::uint32_t board_;
  // Every echo the bus brought from the board, in order (with the FNV-1a digest of that
  // stream), which of them reached the client through the link, and the index of the last one
  // delivered.
  std::vector<Bytes> from_board_;
  std::uint64_t from_board_digest_ = kFnvBasis;
  std::vector<bool> delivered_;
  std::optional<std::uint64_t> last_index_;
  std::uint32_t link_failures_ = 0;
};

}  // namespace ap::sim::xy
