// Dispatch fuzz target: bytes -> stream framer -> callback table, the two halves of the
// board's receive path (Board::handle; what the board does around them, seq, watchdog and
// echoes, is the board target's). The first byte chooses which command IDs have no handler.
// Oracles per frame event:
//   - intact, valid and both handlers installed: exactly two calls, X then Y, with the data;
//   - anything else: no call, and a rejection whose echo formats and reads back.
// Also hand-made frames straight from the bytes: dispatch rejects or calls exactly twice.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "core/xy/frame/callback_table.hpp"
#include "core/xy/frame/stream_framer.hpp"
#include "core/xy/frame/echo_builder.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "crc_repair.hpp"

namespace {

constexpr std::size_t kMaxInput = 600;

namespace f = ap::xy_frame;
using ap::fuzz::require;

struct Calls {
  int count = 0;
  f::Axis axis[2]{};
  std::int32_t data[2]{};
};

f::HandlerStatus handler(void* ctx, f::Axis axis, std::int32_t data) {
  auto* c = static_cast<Calls*>(ctx);
  if (c->count < 2) {
    c->axis[c->count] = axis;
    c->data[c->count] = data;
  }
  ++c->count;
  return (data & 1) != 0 ? f::HandlerStatus::Refused : f::HandlerStatus::Done;
}

struct Absurd {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  std::uint32_t sub = 0;
  std::uint8_t status = 0;
};
f::AxisEcho absurd_axis(void* ctx, f::Axis a) {
  const auto* s = static_cast<const Absurd*>(ctx);
  return {static_cast<ap::xy_codec::EchoStatus>(s->status), static_cast<std::int32_t>(a == f::Axis::X ? s->x : s->y)};
}
std::int32_t absurd_sub(void* ctx, f::SubscriberSlot) { return static_cast<std::int32_t>(static_cast<const Absurd*>(ctx)->sub); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A dozen frames is plenty to reach every framer state; longer inputs only slow the run.
  if (size == 0 || size > kMaxInput) return 0;
  const std::uint8_t missing = data[0];
  f::CallbackTable table;
  for (std::uint32_t id = 0; id < f::CallbackTable::kSize; ++id) {
    if (id % 8 != missing % 8 || (missing & 0x80U) == 0) require(table.install(id, &handler));
  }
  require(!table.install(f::CallbackTable::kSize, &handler));
  Calls calls;
  const std::span<const std::uint8_t> in(data + 1, size - 1);
  f::RawCommandFramer framer;
  for (const std::uint8_t byte : in) {
    const auto event = framer.push(byte);
    if (!event) continue;
    calls = {};
    f::Rejection rejection = event->rejection;
    if (rejection.ok()) {
      const f::Lookup found = table.lookup(event->frame);
      const f::DispatchResult r = table.dispatch(found, event->frame, &calls);
      require(r.rejection == found.rejection);
      rejection = r.rejection;
    }
    // The framer checks syntax and CRC only; the codec's own tables (validate) and the
    // installed slots decide the rest.
    const bool handled = event->rejection.ok() && f::validate(event->frame).ok() &&
                         table.find(static_cast<std::uint32_t>(event->frame.x.id)) != nullptr &&
                         table.find(static_cast<std::uint32_t>(event->frame.y.id)) != nullptr;
    require(handled == rejection.ok());
    if (handled) {
      require(calls.count == 2 && calls.axis[0] == f::Axis::X && calls.axis[1] == f::Axis::Y);
      require(calls.data[0] == event->frame.x.data && calls.data[1] == event->frame.y.data);
      continue;
    }
    require(calls.count == 0);
    std::array<std::uint8_t, ap::xy_codec::kEchoLength> out{};
    require(f::format_echo(f::build_rejection_echo(static_cast<std::uint16_t>(event->frame.seq % 1000U), rejection), out).ok());
    f::EchoFrame echo{};
    require(f::parse_echo(out, echo).ok() && echo.x.status == ap::xy_codec::EchoStatus::FrameRejected);
    require(f::rejection_from_code(echo.x.data) == rejection);
  }
  // Hand-made frame: raw IDs and data, no parser in front.
  if (size >= 11) {
    f::CommandFrame raw;
    raw.x.id = static_cast<ap::xy_codec::CommandId>(data[1]);
    raw.y.id = static_cast<ap::xy_codec::CommandId>(data[2]);
    std::int32_t dx = 0;
    std::int32_t dy = 0;
    std::memcpy(&dx, data + 3, sizeof dx);
    std::memcpy(&dy, data + 7, sizeof dy);
    raw.x.data = dx;
    raw.y.data = dy;
    calls = {};
    const auto r = table.dispatch(raw, &calls);
    require(r.rejection.ok() ? calls.count == 2 : calls.count == 0);
    require(!r.rejection.ok() || f::validate(raw).ok());
  }
  // Echo builder with absurd sources (any status byte, any value, or no source at all): the
  // echo always formats, which Board::send_echoes relies on; so does a rejection echo for
  // whatever rejection_from_code makes of any code.
  if (size >= 17) {
    Absurd a;
    std::memcpy(&a.x, data + 1, sizeof a.x);
    std::memcpy(&a.y, data + 5, sizeof a.y);
    std::memcpy(&a.sub, data + 9, sizeof a.sub);
    a.status = data[13];
    f::SubscriberSlots slots{};
    for (std::size_t k = 0; k < slots.size(); ++k) {
      slots[k] = {static_cast<ap::xy_codec::SubscriberId>(data[14 + k % 3]), data[15 - k % 2]};
    }
    const bool none = (data[16] & 1U) != 0;
    const f::EchoSource src{&a, none ? nullptr : &absurd_axis, (data[16] & 2U) != 0 ? nullptr : &absurd_sub};
    std::array<std::uint8_t, ap::xy_codec::kEchoLength> out{};
    require(f::format_echo(f::build_echo(static_cast<std::uint16_t>(a.x % 1000U), slots, src), out).ok());
    const f::Rejection back = f::rejection_from_code(static_cast<std::int32_t>(a.sub));
    require(f::format_echo(f::build_rejection_echo(static_cast<std::uint16_t>(a.y % 1000U), back), out).ok());
  }
  return 0;
}
