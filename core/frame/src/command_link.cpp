#include "core/frame/command_link.hpp"

namespace ap::frame {

EchoFrame CommandLink::handle(const RawCommandFramer::Event& event) {
  if (!event.rejection.ok()) {
    last_rejection_ = event.rejection;
    return build_rejection_echo(last_seq_, event.rejection);
  }
  const DispatchResult result = table_.dispatch(event.frame, handler_ctx_);
  if (!result.rejection.ok()) {
    ++unhandled_frames_;
    last_rejection_ = result.rejection;
    return build_rejection_echo(last_seq_, result.rejection);
  }
  if (result.x == HandlerStatus::Refused) ++refused_parts_;
  if (result.y == HandlerStatus::Refused) ++refused_parts_;
  ticks_since_accepted_ = 0;
  last_seq_ = event.frame.seq;
  return build_echo(event.frame.seq, event.frame.subs, source_);
}

}  // namespace ap::frame
