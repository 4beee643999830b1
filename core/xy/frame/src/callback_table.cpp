#include "core/xy/frame/callback_table.hpp"

#include "core/xy/frame/command_codec.hpp"

namespace ap::xy_frame {

bool CallbackTable::in_range(std::uint32_t id) { return id < kSize; }

bool CallbackTable::install(std::uint32_t id, Handler handler) {
  if (!in_range(id)) return false;
  handlers_[id] = handler;
  return true;
}

Handler CallbackTable::find(std::uint32_t id) const { return in_range(id) ? handlers_[id] : nullptr; }

Lookup CallbackTable::lookup(const CommandFrame& frame) const {
  Lookup out;
  std::array<Handler, 2> found{};
  const std::array<const AxisCommand*, 2> parts{&frame.x, &frame.y};
  const std::array<std::size_t, 2> id_at{xy_codec::kXIdOffset, xy_codec::kYIdOffset};
  const std::array<std::size_t, 2> data_at{xy_codec::kXDataOffset, xy_codec::kYDataOffset};
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto id = static_cast<std::uint32_t>(parts[i]->id);
    // The table's own bound check: an ID from the wire is an index into handlers_.
    if (!in_range(id)) {
      out.rejection = {xy_codec::FrameError::UnknownCommand, static_cast<std::uint16_t>(id_at[i])};
      return out;
    }
    found[i] = handlers_[id];
    if (!xy_codec::info(static_cast<xy_codec::CommandId>(id)).range.contains(parts[i]->data)) {
      out.rejection = {xy_codec::FrameError::DataOutOfRange, static_cast<std::uint16_t>(data_at[i])};
      return out;
    }
  }
  // seq and the subscriber slots (the command parts pass again; a frame built by hand is
  // checked exactly like one from the wire).
  if (auto r = validate(frame); !r.ok()) {
    out.rejection = r;
    return out;
  }
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (found[i] == nullptr) {
      out.rejection = {xy_codec::FrameError::Unhandled, static_cast<std::uint16_t>(id_at[i])};
      return out;
    }
  }
  out.x = found[0];
  out.y = found[1];
  return out;
}

DispatchResult CallbackTable::dispatch(const Lookup& l, const CommandFrame& frame, void* ctx) const {
  DispatchResult result;
  if (!l.rejection.ok()) {
    result.rejection = l.rejection;
    return result;
  }
  result.x = l.x(ctx, Axis::X, frame.x.data);
  result.y = l.y(ctx, Axis::Y, frame.y.data);
  return result;
}

}  // namespace ap::xy_frame
