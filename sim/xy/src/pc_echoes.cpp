// The echo checks of the simulated PC (pc_echoes.hpp, docs/sim.md "Echo checks"): what the link
// to the PC delivered against what the board sent, checked where the link reports it.
#include "pc_echoes.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "protocol/xy/codec/layout.hpp"
#include "sim/text.hpp"
#include "pc_board.hpp"
#include "pc_transport.hpp"

namespace ap::sim::xy {

void EchoCheck::brought(std::int64_t t, std::span<const std::uint8_t> bytes) {
  if (bytes.size() % xy_codec::kEchoLength != 0) {
    pc_.fail("echo check: board " + std::to_string(board_) + " at " + tstr(t) + ": the bus brought " +
             std::to_string(bytes.size()) + " TX bytes, not whole echoes");
  }
  for (std::size_t k = 0; k + xy_codec::kEchoLength <= bytes.size(); k += xy_codec::kEchoLength) {
    const std::span<const std::uint8_t> echo = bytes.subspan(k, xy_codec::kEchoLength);
    from_board_digest_ = fnv1a(from_board_digest_, echo);
    from_board_.emplace_back(echo.begin(), echo.end());
    delivered_.push_back(false);
  }
}

void EchoCheck::bad(std::int64_t t, const std::string& what) {
  if (++link_failures_ <= 5) pc_.fail("echo check: board " + std::to_string(board_) + " at " + tstr(t) + ": " + what);
}

// The echoes that reached the client are ones the board sent, in order.
void EchoCheck::left(std::int64_t t, std::span<const std::uint8_t> bytes, std::span<const FrameTag> tags) {
  if (bytes.size() != tags.size() * xy_codec::kEchoLength) {
    bad(t, std::to_string(bytes.size()) + " bytes left the link for " + std::to_string(tags.size()) + " echoes");
    return;
  }
  for (std::size_t k = 0; k < tags.size(); ++k) {
    const FrameTag& g = tags[k];
    const std::string n = "echo #" + std::to_string(g.index);
    if (g.index >= from_board_.size()) {
      bad(t, n + " left the link but the board never sent it");
      continue;
    }
    const Bytes& sent = from_board_[g.index];
    std::size_t differ = 0;
    for (std::size_t i = 0; i < xy_codec::kEchoLength; ++i) differ += bytes[k * xy_codec::kEchoLength + i] != sent[i] ? 1U : 0U;
    // Not corrupted: byte-identical. Corrupted on purpose: one byte per corruption (two
    // corruptions may hit the same byte, and only then can masks cancel).
    if (g.corruptions == 0 && differ != 0) bad(t, n + " differs from what the board sent in " + std::to_string(differ) + " bytes");
    if (g.corruptions == 1 && differ != 1) {
      bad(t, n + " corrupted once by the link but differs in " + std::to_string(differ) + " bytes");
    }
    if (g.corruptions > 1 && differ > g.corruptions) bad(t, n + " differs in more bytes than the link corrupted");
    // Order: each echo after the last one delivered, except the second copy of a duplicate
    // (the same one again) and a frame the link held back on purpose (reordered).
    if (last_index_ && g.index <= *last_index_ && !(g.duplicate && g.index == *last_index_) && !g.reordered) {
      bad(t, n + " arrived after echo #" + std::to_string(*last_index_) + " (out of order, no reorder or duplicate fault)");
    }
    if (!g.reordered && (!last_index_ || g.index > *last_index_)) last_index_ = g.index;
    delivered_[g.index] = true;
  }
}

// The board-side echo model (every echo the core sent, docs/sim.md) and the PC-side
// accounting of the echoes: the bus carried the board's TX stream exactly, and the link
// lost no more of it than it says.
void EchoCheck::finish(BoardPc& b, std::int64_t t) {
  const std::string who = "board " + std::to_string(b.id);
  std::istringstream em(env(pc_, b, "probe echo_model", t));
  std::uint64_t checked = 0, disagreements = 0;
  if (!(em >> checked >> disagreements)) {
    pc_.fail("echo model: " + who + ": no answer to probe echo_model");
  } else {
    b.verdict.echoes_model_checked = checked;
    b.verdict.echo_disagreements = disagreements;
    for (std::uint64_t k = 0; k < std::min<std::uint64_t>(disagreements, 3); ++k) {
      std::string text;
      for (std::size_t off = 0; off < 2000; off += 100) {
        const std::string part = env(pc_, b, "probe echo_model." + std::to_string(k) + "." + std::to_string(off), t);
        if (part.empty()) break;
        text += part;
      }
      pc_.fail("echo model (board-side, every echo): " + who + ": " + text);
    }
    if (disagreements > 3) pc_.fail("echo model: " + who + ": " + std::to_string(disagreements - 3) + " more disagreements");
  }
  std::istringstream es(env(pc_, b, "probe echo_sent." + std::to_string(from_board_.size()), t));
  std::uint64_t total = 0, digest = 0, queued = 0;
  if (!(es >> total >> digest >> queued)) {
    pc_.fail("echo check: " + who + ": the board sent fewer echoes than the bus brought (" +
             std::to_string(from_board_.size()) + ")");
  } else {
    if (digest != from_board_digest_) pc_.fail("echo check: " + who + ": the echoes the bus brought are not the board's TX stream");
    if (total != from_board_.size() + queued) {
      pc_.fail("echo check: " + who + ": the board sent " + std::to_string(total) + " echoes, the bus brought " +
               std::to_string(from_board_.size()) + " and " + std::to_string(queued) + " wait in its TX queue");
    }
  }
  const auto missing = static_cast<std::uint64_t>(std::count(delivered_.begin(), delivered_.end(), false));
  const LinkStats& up = b.verdict.to_pc;
  const std::uint64_t accounted = up.dropped + up.cut + b.up->in_flight();
  b.verdict.echoes_from_board = from_board_.size();
  if (missing > accounted) {
    pc_.fail("echo check: " + who + ": " + std::to_string(missing) + " echoes the board sent never reached the PC; the link " +
             "dropped, cut or still holds " + std::to_string(accounted));
  }
}

}  // namespace ap::sim::xy
