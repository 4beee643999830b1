#include "core/frame/callback_table.hpp"

#include "core/frame/command_codec.hpp"

namespace ap::frame {

bool CallbackTable::in_range(std::uint32_t id) { return id < kSize; }

bool CallbackTable::install(std::uint32_t id, Handler handler) {
  if (!in_range(id)) return false;
  handlers_[id] = handler;
  return true;
}

Handler CallbackTable::find(std::uint32_t id) const { return in_range(id) ? handlers_[id] : nullptr; }

DispatchResult CallbackTable::dispatch(const CommandFrame& frame, void* ctx) const {
  DispatchResult result;
  if (auto r = validate(frame); !r.ok()) {
    result.rejection = r;
    return result;
  }
  const Handler hx = find(static_cast<std::uint32_t>(frame.x.id));
  if (hx == nullptr) {
    result.rejection = {codec::FrameError::Unhandled, static_cast<std::uint16_t>(codec::kXIdOffset)};
    return result;
  }
  const Handler hy = find(static_cast<std::uint32_t>(frame.y.id));
  if (hy == nullptr) {
    result.rejection = {codec::FrameError::Unhandled, static_cast<std::uint16_t>(codec::kYIdOffset)};
    return result;
  }
  result.x = hx(ctx, Axis::X, frame.x.data);
  result.y = hy(ctx, Axis::Y, frame.y.data);
  return result;
}

}  // namespace ap::frame
