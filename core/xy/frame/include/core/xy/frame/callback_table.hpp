#pragma once
// The callback table (the thesis's CallbackArray): handler function pointers indexed by
// command ID. Unlike the thesis, every lookup is bounds-checked and an empty slot is a
// typed rejection, never a call through a null pointer.
//
// Who installs what: the board supervisor (core/xy/board) owns one table and installs one
// handler per command it implements, then calls dispatch() with itself as `ctx` for every
// accepted frame. Handlers are plain functions, not std::function, so the table is a
// fixed array in .bss with no heap.
//
// Dispatch contract (Klipper style): the frame may come straight from the link layer
// (decode_command: intact, but IDs 00..99 unchecked), so lookup() is what gives it a
// meaning. Per axis part, in wire order: the table's own bound check on the ID (this is the
// check that rejects an ID outside the table, unknown_command), the data range of that
// command, then seq and subscriber slots (validate()), then both handlers must be
// installed (unhandled). Both handlers are looked up before either runs, so a frame is
// either executed completely (X handler once, then Y handler once) or not at all.
// Unit-scope commands (xy_codec::Scope::Unit) reach the handler once per axis part that
// carries them; such handlers must be idempotent.
#include <array>
#include <cstddef>
#include <cstdint>

#include "protocol/xy/codec/commands.hpp"
#include "core/xy/frame/frames.hpp"

namespace ap::xy_frame {

enum class HandlerStatus : std::uint8_t {
  Done,     // command taken
  Refused,  // valid, but not allowed now (blocked, asleep, ...); the echo status says why
};

using Handler = HandlerStatus (*)(void* ctx, Axis axis, std::int32_t data);

struct Lookup {
  Rejection rejection;  // not ok(): x and y are null
  Handler x = nullptr;
  Handler y = nullptr;
};

struct DispatchResult {
  Rejection rejection;  // not ok(): no handler ran
  HandlerStatus x = HandlerStatus::Done;
  HandlerStatus y = HandlerStatus::Done;
};

class CallbackTable {
 public:
  static constexpr std::size_t kSize = xy_codec::kCommandCount;

  // False (and nothing stored) when id is outside the table.
  bool install(std::uint32_t id, Handler handler);
  bool install(xy_codec::CommandId id, Handler handler) { return install(static_cast<std::uint32_t>(id), handler); }
  // nullptr when id is outside the table or nothing is installed.
  Handler find(std::uint32_t id) const;

  // Everything dispatch() checks, without running anything.
  Lookup lookup(const CommandFrame& frame) const;
  // Runs the handlers `l` found for `frame`, X then Y; nothing when `l` is a rejection. The
  // board looks a frame up once, decides (blocked, seq) and then runs this.
  DispatchResult dispatch(const Lookup& l, const CommandFrame& frame, void* ctx) const;
  DispatchResult dispatch(const CommandFrame& frame, void* ctx) const { return dispatch(lookup(frame), frame, ctx); }

 private:
  static bool in_range(std::uint32_t id);

  // A plain array on purpose: clang's -fsanitize=bounds checks every index into it, so a
  // bound check that lets kSize through is a finding (std::array::operator[] is not
  // checked under libstdc++ without assertions, and ASan cannot see a read that stays
  // inside the enclosing object).
  Handler handlers_[kSize]{};  // NOLINT(*-avoid-c-arrays)
};

}  // namespace ap::xy_frame
