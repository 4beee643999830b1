#include "core/xy/frame/echo_builder.hpp"

#include <algorithm>

#include "protocol/xy/codec/statuses.hpp"
#include "protocol/xy/codec/subscribers.hpp"

namespace ap::xy_frame {

namespace c = ap::xy_codec;

namespace {

std::int32_t clamp(std::int32_t v, c::Range r) { return std::clamp(v, r.min, r.max); }

AxisEcho sanitize(AxisEcho e) {
  const auto* info = c::find_status(static_cast<std::uint32_t>(e.status));
  if (info == nullptr) return {c::EchoStatus::Fault, 0};
  return {e.status, clamp(e.data, info->range)};
}

}  // namespace

EchoFrame build_echo(std::uint16_t seq, const SubscriberSlots& requested, const EchoSource& source) {
  EchoFrame echo;
  echo.seq = static_cast<std::uint16_t>(seq % c::kSeqModulo);
  if (source.axis != nullptr) {
    echo.x = sanitize(source.axis(source.ctx, Axis::X));
    echo.y = sanitize(source.axis(source.ctx, Axis::Y));
  }
  for (std::size_t i = 0; i < requested.size(); ++i) {
    const auto* info = c::find_subscriber(static_cast<std::uint32_t>(requested[i].id));
    if (info == nullptr || !info->arg_range.contains(requested[i].arg) || info->id == c::SubscriberId::None) {
      continue;  // empty packet: a parsed command never gets here with a bad slot
    }
    const std::int32_t raw = source.subscriber != nullptr ? source.subscriber(source.ctx, requested[i]) : 0;
    echo.subs[i] = {requested[i], clamp(raw, info->range)};
  }
  return echo;
}

std::int32_t rejection_code(Rejection r) {
  const std::int32_t offset = std::min<std::int32_t>(r.offset, c::kRejectReasonScale - 1);
  return static_cast<std::int32_t>(r.error) * c::kRejectReasonScale + offset;
}

Rejection rejection_from_code(std::int32_t code) {
  if (code < 0) return {c::FrameError::None, 0};
  return {static_cast<c::FrameError>(code / c::kRejectReasonScale), static_cast<std::uint16_t>(code % c::kRejectReasonScale)};
}

EchoFrame build_rejection_echo(std::uint16_t last_seq, Rejection rejection) {
  EchoFrame echo;
  echo.seq = static_cast<std::uint16_t>(last_seq % c::kSeqModulo);
  const std::int32_t code = rejection_code(rejection);
  echo.x = {c::EchoStatus::FrameRejected, code};
  echo.y = {c::EchoStatus::FrameRejected, code};
  return echo;
}

}  // namespace ap::xy_frame
