// The receive path (docs/board.md "One cycle (tick) in order" step 3): which frame runs, which
// is only answered and which is dropped is decided here and nowhere else. The callback table
// the constructor fills (docs/protocol.md "Dispatch: the callback table", the command table in
// "ID tables"), the UART ring uart_rx() fills, and one frame event: a rejected frame
// (docs/protocol.md "What a rejected frame may change"), the BLE session gate (G15), the
// delivery window that tells a new frame from a repeat or an older one and takes at most one
// new frame a cycle (docs/protocol.md "Delivery", "Two frames in one cycle"), a frame taken
// while blocked (§7.5.2), then the dispatch. The handlers are commands.cpp's, parameters.cpp's
// and path_commands.cpp's; the echo each event queues is built by echo.cpp.
#include "core/xy/board/board.hpp"

#include "protocol/xy/codec/commands.hpp"

namespace ap::xy_board {

namespace c = ap::xy_codec;
namespace tmc = ap::xy_tmc2130;
using xy_frame::HandlerStatus;

Board::Board(const Hardware& hw)
    : hw_(hw),
      store_(hw.fram),
      drivers_{tmc::Driver(hw.tmc[0]), tmc::Driver(hw.tmc[1])},
      tmp117_(hw.i2c, xy_tmp117::kAddressGnd),
      gyro_(hw.i2c, xy_icm20789::kAddressAd0Low) {
  table_.install(c::CommandId::Nop, &Board::on_nop);
  table_.install(c::CommandId::Stop, &Board::on_stop);
  table_.install(c::CommandId::Jog, &Board::on_jog);
  table_.install(c::CommandId::Goto, &Board::on_goto);
  table_.install(c::CommandId::Move, &Board::on_move);
  table_.install(c::CommandId::GotoSlow, &Board::on_goto_slow);
  table_.install(c::CommandId::MoveSlow, &Board::on_move_slow);
  table_.install(c::CommandId::Home, &Board::on_home);
  table_.install(c::CommandId::SetFastSpeed, &Board::on_param_id<c::CommandId::SetFastSpeed>);
  table_.install(c::CommandId::SetSlowSpeed, &Board::on_param_id<c::CommandId::SetSlowSpeed>);
  table_.install(c::CommandId::SetAccel, &Board::on_param_id<c::CommandId::SetAccel>);
  table_.install(c::CommandId::SetStartSpeed, &Board::on_param_id<c::CommandId::SetStartSpeed>);
  table_.install(c::CommandId::SetPitch, &Board::on_param_id<c::CommandId::SetPitch>);
  table_.install(c::CommandId::SetSteps, &Board::on_param_id<c::CommandId::SetSteps>);
  table_.install(c::CommandId::SetMicrosteps, &Board::on_param_id<c::CommandId::SetMicrosteps>);
  table_.install(c::CommandId::SetIrun, &Board::on_param_id<c::CommandId::SetIrun>);
  table_.install(c::CommandId::SetIhold, &Board::on_param_id<c::CommandId::SetIhold>);
  table_.install(c::CommandId::PeriphOff, &Board::on_periph_off);
  table_.install(c::CommandId::PeriphOn, &Board::on_periph_on);
  table_.install(c::CommandId::SaveParams, &Board::on_save);
  table_.install(c::CommandId::ClearFault, &Board::on_clear);
  table_.install(c::CommandId::PathLine, &Board::on_path_part<c::CommandId::PathLine>);
  table_.install(c::CommandId::PathCentre, &Board::on_path_part<c::CommandId::PathCentre>);
  table_.install(c::CommandId::PathArcCw, &Board::on_path_part<c::CommandId::PathArcCw>);
  table_.install(c::CommandId::PathArcCcw, &Board::on_path_part<c::CommandId::PathArcCcw>);
  table_.install(c::CommandId::PathEnd, &Board::on_path_end);
  derived_ = derive(store_.current());
}

void Board::uart_rx(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    if (rx_count_ == rx_.size()) {
      ++counters_.rx_overruns;
      continue;
    }
    rx_[(rx_head_ + rx_count_) % rx_.size()] = b;
    ++rx_count_;
  }
}

void Board::receive() {
  // At most one new frame is taken per cycle (docs/protocol.md "Two frames in one cycle"): the
  // handlers only store this cycle's motion command and the axes apply it when they step, so
  // a second new frame would replace the first one unrun while both were answered. The bytes
  // behind a taken frame wait in the ring for the next cycle (1 ms later); repeats, older
  // frames and rejections before it are answered in this cycle as usual.
  while (rx_count_ > 0 && echo_count_ < echoes_.size() && !taken_this_cycle_) {
    const std::uint8_t b = rx_[rx_head_];
    rx_head_ = (rx_head_ + 1) % rx_.size();
    --rx_count_;
    if (auto e = framer_.push(b)) handle(*e);
  }
}

void Board::handle(const xy_frame::RawCommandFramer::Event& e) {
  if (!e.rejection.ok()) {
    // A malformed frame is answered but changes nothing else: no handler, no watchdog
    // refresh, last_seq kept (docs/protocol.md, "What a rejected frame may change").
    if (!session_open_) return;
    echoes_[echo_count_++] = PendingEcho{true, e.rejection, last_seq_, {}, false};
    return;
  }
  if (!session_open_) {
    // G15: only a Data Session carries commands; bytes seen otherwise are line noise from
    // the module's own traffic and nobody is listening for an answer.
    ++counters_.gated_frames;
    return;
  }
  // The frame arrived intact; the callback table decides whether it means anything (an ID
  // outside the table, data out of range, an empty slot). Such a frame is rejected like a
  // malformed one, blocked or not.
  const xy_frame::Lookup found = table_.lookup(e.frame);
  if (const xy_frame::Rejection r = found.rejection; !r.ok()) {
    ++counters_.unhandled_frames;
    echoes_[echo_count_++] = PendingEcho{true, r, last_seq_, {}, false};
    return;
  }
  // Delivery (docs/protocol.md "Delivery"): the client repeats a frame until it is answered,
  // and the link may duplicate, delay and reorder, so a frame runs only when its seq is newer
  // than the last one taken. A repeat is answered with that frame's outcome and still proves
  // the link (the watchdog is fed, as by the frame itself); an older frame is answered with the
  // seq of the last one taken, which tells its sender where the board stands.
  const xy_codec::SeqOrder order = have_seq_ ? xy_codec::seq_order(last_seq_, e.frame.seq) : xy_codec::SeqOrder::New;
  if (order != xy_codec::SeqOrder::New) {
    if (order == xy_codec::SeqOrder::Repeat) {
      ++counters_.repeated_frames;
      if (block_ == Block::None) frame_this_cycle_ = true;
    } else {
      ++counters_.older_frames;
    }
    echoes_[echo_count_++] = PendingEcho{false, {}, last_seq_, e.frame.subs, true};
    return;
  }
  have_seq_ = true;
  last_seq_ = e.frame.seq;
  taken_this_cycle_ = true;
  if (hw_.frame_taken != nullptr) hw_.frame_taken(hw_.ctx, e.frame);
  if (block_ != Block::None) {
    // §7.5.2: commands cannot change the blocked state, so none is executed; the echo still
    // goes out so the PC can show why the unit does not move.
    ++counters_.blocked_frames;
    echoes_[echo_count_++] = PendingEcho{false, {}, e.frame.seq, e.frame.subs, false};
    return;
  }
  const xy_frame::DispatchResult r = table_.dispatch(found, e.frame, this);
  ++counters_.dispatched_frames;
  if (r.x == HandlerStatus::Refused) ++counters_.refused_parts;
  if (r.y == HandlerStatus::Refused) ++counters_.refused_parts;
  commit_path_frame(e.frame);
  frame_this_cycle_ = true;
  echoes_[echo_count_++] = PendingEcho{false, {}, e.frame.seq, e.frame.subs, false};
}

}  // namespace ap::xy_board
