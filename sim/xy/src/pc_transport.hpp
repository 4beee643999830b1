// Driving the delivery client (pc/xy/client) over the fault links and the bus (docs/sim.md "The
// simulated PC", "The bus protocol of a run"): the only code of the simulated PC that moves
// bytes. It hands what passes to the checks (the links' observers, the delivery check, the
// expectations' readings) and does no checking itself, so a change to a check does not touch
// the path the frames take.
#pragma once

#include <cstdint>
#include <string>

#include "pc/dds/bus.hpp"
#include "pc/xy/client/client.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "pc_board.hpp"

namespace ap::sim::xy {

// Waits (20 s) until every board's endpoint is on the bus.
void connect(const Boards& boards);

// An environment command (docs/sim.md "The bus protocol of a run") and the value of its `ok`
// reply; an `err` reply fails the run.
std::string env(PcContext& pc, BoardPc& b, const std::string& line, std::int64_t t);

// The board's answer to bus command `seq` (skipping older ones).
dds::EchoSample wait_echo(BoardPc& b, std::uint64_t seq);

// A user command to the client, which delivers it exactly once or reports why not.
void submit(BoardPc& b, xy_client::Part part, xy_codec::CommandId id, std::int32_t data, std::int64_t t);

// One lockstep step of every board: what the client sends now goes through the link to the
// board, one bus Step each (all boards first, then all echoes), the echoes through the link
// back into the client, and the commands they settle to the delivery check.
void step(PcContext& pc, Boards& boards, std::int64_t t);

// Sends every board the shutdown command and waits for its answer.
void shut_down(Boards& boards, std::int64_t t);

}  // namespace ap::sim::xy
