// The outcome oracle (docs/protocol.md "Outcomes", docs/sim.md "Outcome check"): the outcome
// the client reports for a command against what the board did with the frame that carried
// it. What the board did is the echo model's account of that frame (models/xy/echo: run, refused
// part, or blocked), not the board's answer and not the client's reading of it, so a wrong
// answer (a repeat telling a block of today) or a wrong reading shows as a disagreement.
//
// The board side keeps the fate of every frame it took (by seq, the last one taken wins: a seq
// comes back after 1000 frames or after a power cycle) and hands it over the bus as text; the
// PC side checks each report as it settles. Used by the simulated PC (every scenario and
// storm) and by the board-and-client property (properties/xy/board).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "models/xy/echo/echo_model.hpp"
#include "pc/xy/client/client.hpp"

namespace ap::sim::xy {

// "BLOCKED XID XDATA YID YDATA XREFUSED YREFUSED" (a refusal as its command ID, -1: none): the
// bus form of a fate (a bus reply carries at most 100-odd bytes).
std::string fate_text(const model::xy_echo::FrameFate& f);
std::optional<model::xy_echo::FrameFate> parse_fate(std::string_view text);

// The outcome a command in part `part` of a frame with this fate must be reported with:
// blocked, refused (its part refused), else done (it ran).
xy_client::Outcome outcome_of(const model::xy_echo::FrameFate& f, std::size_t part);

// nullopt when the report agrees with the board; else what disagrees, readable. `fate` is the
// fate of the frame with the report's seq (nullopt: the board took no frame with that seq).
// Done, refused and blocked need that frame with this command in the report's part and the
// matching fate; superseded, link_down and invalid need no frame at all (they never left);
// unconfirmed is at most once, which the frame count of the delivery check covers.
std::optional<std::string> check_outcome(const xy_client::Report& r, const std::optional<model::xy_echo::FrameFate>& fate);

}  // namespace ap::sim::xy
