// Driving the delivery client over the fault links and the bus (pc_transport.hpp, docs/sim.md
// "The simulated PC"): the path the bytes take, kept free of checks so that what it moves is
// plain to read and a check cannot change it.
#include "pc_transport.hpp"

#include <chrono>
#include <span>
#include <stdexcept>
#include <utility>

#include "protocol/xy/codec/layout.hpp"
#include "sim/serve_loop.hpp"

namespace ap::sim::xy {

namespace sc = ap::sim::xy::scenario;

BoardPc::BoardPc(PcContext& pc, const dds::ParticipantPtr& pp, std::uint32_t board)
    : id(board), echoes(pc, board) {
  const sc::Scenario& s = pc.s;
  ep = std::make_unique<dds::PcEndpoint>(pp, board);
  xy_client::Config cc;
  cc.keepalive_us = s.period_us;
  cc.first_seq = s.first_seq;
  cc.factory = true;  // the simulated PC is a developer's tool: it sets the machine up too
  client = std::make_unique<xy_client::Client>(cc);
  down = std::make_unique<FaultLink>(s.faults, sc::Direction::to_board, s.seed * 1'000'003ULL + board * 2ULL, &safety);
  up = std::make_unique<FaultLink>(s.faults, sc::Direction::to_pc, s.seed * 1'000'003ULL + board * 2ULL + 1ULL, &echoes);
  verdict.board = board;
}

void connect(const Boards& boards) {
  for (const auto& b : boards) {
    if (!b->ep->wait_matched(std::chrono::seconds(20))) {
      throw std::runtime_error("board " + std::to_string(b->id) + " did not appear on the bus within 20 s");
    }
  }
}

std::string env(PcContext& pc, BoardPc& b, const std::string& line, std::int64_t t) {
  const std::vector<std::uint8_t> bytes(line.begin(), line.end());
  const std::uint64_t seq = b.ep->send(bytes, static_cast<std::uint64_t>(t), dds::kFlagEnv);
  ++pc.round_trips;
  const dds::EchoSample e = wait_echo(b, seq);
  std::string reply(e.bytes.begin(), e.bytes.end());
  if (reply.rfind("ok", 0) != 0) pc.fail("board " + std::to_string(b.id) + ": environment command '" + line + "': " + reply);
  return reply.size() > 3 ? reply.substr(3) : std::string();
}

dds::EchoSample wait_echo(BoardPc& b, std::uint64_t seq) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  for (;;) {
    auto e = b.ep->take_echo(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()));
    if (!e) throw std::runtime_error("board " + std::to_string(b.id) + " did not answer bus command " + std::to_string(seq));
    if (e->cmd_seq == seq) return std::move(*e);
  }
}

void submit(BoardPc& b, xy_client::Part part, xy_codec::CommandId id, std::int32_t data, std::int64_t t) {
  const xy_client::Command c{part, {id, data}};
  const std::uint16_t next = b.client->next_seq();
  const xy_client::Ticket tk = b.client->submit(c, t);
  b.delivery.submitted(c, tk, next, t);
}

namespace {

// What rides in every new frame: the held jog levels and the subscriber slots.
xy_client::Extras extras(const PcContext& pc, const BoardPc& b) {
  xy_client::Extras e;
  for (std::size_t i = 0; i < 2; ++i) e.jog[i] = b.keys[i].jog;
  std::size_t slot = 0;
  for (const auto id : pc.subscribed) {
    if (slot >= (pc.param_slots.empty() ? xy_codec::kSubscriberSlots : xy_codec::kSubscriberSlots - 1)) break;
    e.subs[slot++] = {id, 0};
  }
  if (!pc.param_slots.empty()) {
    const std::uint32_t n = b.client->counters().new_frames;
    e.subs[xy_codec::kSubscriberSlots - 1] = {xy_codec::SubscriberId::Param, pc.param_slots[n % pc.param_slots.size()]};
  }
  return e;
}

void receive(BoardPc& b, const Bytes& in, std::int64_t t) {
  for (const xy_client::EchoEvent& ev : b.client->receive(std::span<const std::uint8_t>(in), t)) {
    b.delivery.echo(ev);
    b.seen.echo(ev);
  }
}

}  // namespace

void step(PcContext& pc, Boards& boards, std::int64_t t) {
  for (auto& bp : boards) {
    BoardPc& b = *bp;
    if (const auto text = b.client->poll(t, extras(pc, b))) {
      b.down->push(t, Bytes(text->begin(), text->end()), b.verdict.to_board);
    }
    const Bytes out = b.down->pop(t, 3 * xy_codec::kCommandLength, b.verdict.to_board);
    b.cmd_seq = b.ep->send(out, static_cast<std::uint64_t>(t));
    ++pc.round_trips;
  }
  for (auto& bp : boards) {
    BoardPc& b = *bp;
    const dds::EchoSample e = wait_echo(b, b.cmd_seq);
    b.safety.sampled(b.have_tel ? &b.tel : nullptr, e.telemetry);
    b.tel = e.telemetry;
    b.have_tel = true;
    b.echoes.brought(t, e.bytes);
    for (std::size_t k = 0; k + xy_codec::kEchoLength <= e.bytes.size(); k += xy_codec::kEchoLength) {
      b.up->push(t,
                 Bytes(e.bytes.begin() + static_cast<std::ptrdiff_t>(k),
                       e.bytes.begin() + static_cast<std::ptrdiff_t>(k + xy_codec::kEchoLength)),
                 b.verdict.to_pc);
    }
    const Bytes in = b.up->pop(t, 64 * xy_codec::kEchoLength, b.verdict.to_pc);
    if (!in.empty()) receive(b, in, t);
    b.delivery.settle(pc, b, t);
  }
}

void shut_down(Boards& boards, std::int64_t t) {
  for (auto& bp : boards) {
    const std::uint64_t seq = bp->ep->send({}, static_cast<std::uint64_t>(t), dds::kFlagShutdown);
    (void)wait_echo(*bp, seq);
  }
}

}  // namespace ap::sim::xy
