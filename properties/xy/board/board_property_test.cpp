// Properties of the board core over random frames (RapidCheck).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <optional>

#include "sim/xy/rig/board_rig.hpp"
#include "core/xy/frame/echo_builder.hpp"
#include "protocol/xy/codec/commands.hpp"
#include "protocol/xy/codec/statuses.hpp"

using namespace ap;
using namespace ap::xy_board;
using ap::sim::xy::Rig;

namespace {

xy_frame::CommandFrame any_frame() {
  xy_frame::CommandFrame f;
  f.seq = *rc::gen::inRange<std::uint16_t>(0, 1000);
  const auto axis_cmd = [] {
    const auto& info = xy_codec::kCommands[*rc::gen::inRange<std::size_t>(0, xy_codec::kCommandCount)];
    return xy_frame::AxisCommand{info.id, *rc::gen::inRange<std::int32_t>(info.range.min, info.range.max + 1)};
  };
  f.x = axis_cmd();
  f.y = axis_cmd();
  return f;
}

}  // namespace

// A frame damaged anywhere (one byte replaced) is answered by a FRAME_REJECTED echo and
// leaves the axes, the parameters and the last accepted seq exactly as a twin board that
// never saw it.
RC_GTEST_PROP(BoardProps, CorruptedFrameChangesOnlyCountersAndEcho, ()) {
  Rig a;
  Rig b;
  a.boot();
  b.boot();
  // At least one tick: the jog's frame is taken in it, and the damaged bytes that follow are
  // then handled in a tick of their own (one new frame per tick, docs/protocol.md "Two frames
  // in one cycle"; with no tick the damaged frame waited behind the jog's).
  const int warm = *rc::gen::inRange(1, 400);
  for (Rig* r : {&a, &b}) {
    r->send(xy_codec::CommandId::Jog, 2, xy_codec::CommandId::Jog, -1);
    r->tick(warm);
  }
  auto bytes = Rig::bytes_of(any_frame());
  const auto pos = *rc::gen::inRange<std::size_t>(0, bytes.size());
  const auto with = *rc::gen::suchThat(rc::gen::arbitrary<std::uint8_t>(), [&](std::uint8_t v) { return v != bytes[pos]; });
  bytes[pos] = with;
  xy_frame::CommandFrame parsed;
  RC_PRE(!xy_frame::parse_command(bytes, parsed).ok());
  // Terminate a frame cut short by an early start or end character so the framer answers now.
  a.send_raw(bytes);
  const std::array<std::uint8_t, 1> flush{static_cast<std::uint8_t>('>')};
  if (a.board->counters().framer.rejected_frames == 0) a.send_raw(flush);
  a.tick();
  b.tick();
  for (const Axis ax : {Axis::X, Axis::Y}) {
    RC_ASSERT(a.ax(ax).pos == b.ax(ax).pos);
    RC_ASSERT(a.ax(ax).v == b.ax(ax).v);
    RC_ASSERT(a.ax(ax).mode == b.ax(ax).mode);
    RC_ASSERT(a.ax(ax).target == b.ax(ax).target);
  }
  RC_ASSERT(a.board->store().current() == b.board->store().current());
  RC_ASSERT(a.board->store().sequence() == b.board->store().sequence());
  RC_ASSERT(a.board->last_seq() == b.board->last_seq());
  RC_ASSERT(a.board->counters().dispatched_frames == b.board->counters().dispatched_frames);
  RC_ASSERT(a.board->link_alive() == b.board->link_alive());
  if (a.board->counters().framer.rejected_frames > 0) {
    const auto e = a.last_echo();
    RC_ASSERT(e.has_value());
    RC_ASSERT(e->x.status == xy_codec::EchoStatus::FrameRejected);
    RC_ASSERT(e->seq == b.board->last_seq());
  }
  // When the framer saw the whole frame alone, the echo names the parser's own reason.
  const auto start = std::count(bytes.begin(), bytes.end(), static_cast<std::uint8_t>('>'));
  const auto end = std::count(bytes.begin(), bytes.end(), static_cast<std::uint8_t>(';'));
  if (bytes.front() == '>' && bytes.back() == ';' && start == 1 && end == 1) {
    const auto e = a.last_echo();
    RC_ASSERT(e.has_value());
    RC_ASSERT(xy_frame::rejection_from_code(e->x.data) == xy_frame::parse_command(bytes, parsed));
  }
}

// Every dispatched frame is answered exactly once, at the end of the cycle it arrived in,
// with its own seq, whatever mix of commands it carries.
// Every accepted frame gets one echo, carrying the seq of the last frame taken (docs/protocol.md
// "Delivery"): its own when it is new (the first after power-up, or 1..499 ahead of the last
// one taken, mod 1000), else the last one's. Seqs are drawn close together and far apart.
RC_GTEST_PROP(BoardProps, EveryAcceptedFrameGetsOneEchoWithTheLastSeqTaken, ()) {
  Rig r;
  r.boot();
  std::optional<int> taken;
  const int n = *rc::gen::inRange(1, 20);
  for (int i = 0; i < n; ++i) {
    xy_frame::CommandFrame f = any_frame();
    if (taken && *rc::gen::inRange(0, 2) == 0) {
      f.seq = static_cast<std::uint16_t>((*taken + *rc::gen::inRange(-3, 4) + 1000) % 1000);
    }
    const auto bytes = Rig::bytes_of(f);
    const std::size_t before = r.tx.size();
    r.send_raw(bytes);
    r.tick();
    RC_ASSERT(r.tx.size() == before + 1);
    const auto e = r.last_echo();
    RC_ASSERT(e.has_value());
    const int ahead = taken ? (f.seq - *taken + 1000) % 1000 : 1;
    if (ahead >= 1 && ahead <= 499) taken = f.seq;
    RC_ASSERT(e->seq == *taken);
    r.tick(*rc::gen::inRange(0, 150));
  }
}
