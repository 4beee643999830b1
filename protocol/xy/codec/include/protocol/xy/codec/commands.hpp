#pragma once
// The command table: the single source of truth for command IDs on both sides of the link.
// The ID is the index into the firmware's callback table, so the table is dense (entry i has
// ID i) and its size is the callback table's size. Append new commands; never renumber.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "protocol/xy/codec/id_table.hpp"
#include "protocol/xy/codec/range.hpp"

namespace ap::xy_codec {

enum class CommandId : std::uint8_t {
  Nop = 0,
  Stop = 1,
  Jog = 2,
  Goto = 3,
  Move = 4,
  Home = 5,
  SetFastSpeed = 6,
  SetSlowSpeed = 7,
  SetAccel = 8,
  SetStartSpeed = 9,
  SetPitch = 10,
  SetSteps = 11,
  SetMicrosteps = 12,
  SetIrun = 13,
  SetIhold = 14,
  PeriphOff = 15,
  PeriphOn = 16,
  SaveParams = 17,
  ClearFault = 18,
  PathLine = 19,
  PathCentre = 20,
  PathArcCw = 21,
  PathArcCcw = 22,
  PathEnd = 23,
  GotoSlow = 24,
  MoveSlow = 25,
};

// Unit-wide commands act once per frame whichever axis part carries them; the other part
// should be a no-op. Axis commands act on the axis of their part.
enum class Scope : std::uint8_t { Axis, Unit };

// Jog data: sign = direction, magnitude = speed level. 0 = key released (ramped stop, G20).
inline constexpr std::int32_t kJogSlow = 1;
inline constexpr std::int32_t kJogFast = 2;

struct CommandInfo {
  CommandId id;
  std::string_view key;      // readable name used by `axisproof frame encode`
  Scope scope;
  std::string_view meaning;  // what the data field means
  std::string_view unit;
  Range range;               // allowed data; DummyData commands allow only 0
};

// In flash on the Cortex-M4 (arm-none-eabi-gcc 12 puts an `inline constexpr` table with
// pointers into .data otherwise).
[[gnu::section(".rodata.ap.codec.commands")]] inline constexpr std::array kCommands = {
    CommandInfo{CommandId::Nop, "nop", Scope::Axis, "DummyData (keep-alive)", "-", {0, 0}},
    CommandInfo{CommandId::Stop, "stop", Scope::Axis, "DummyData; ramped stop with deceleration", "-", {0, 0}},
    CommandInfo{CommandId::Jog, "jog", Scope::Axis, "direction x speed level: +-1 slow, +-2 fast, 0 released", "level", {-2, 2}},
    CommandInfo{CommandId::Goto, "goto", Scope::Axis, "absolute target position", "um", {0, 999999}},
    CommandInfo{CommandId::Move, "move", Scope::Axis, "relative move from the current position", "um", {-99999, 999999}},
    CommandInfo{CommandId::Home, "home", Scope::Axis, "DummyData; reference against the min endstop", "-", {0, 0}},
    CommandInfo{CommandId::SetFastSpeed, "fast", Scope::Axis, "fast manual/positioning speed", "um/s", {1, 999999}},
    CommandInfo{CommandId::SetSlowSpeed, "slow", Scope::Axis, "slow manual and positioning speed", "um/s", {1, 999999}},
    CommandInfo{CommandId::SetAccel, "accel", Scope::Axis, "acceleration and deceleration", "um/s^2", {1, 999999}},
    CommandInfo{CommandId::SetStartSpeed, "start", Scope::Axis, "start/stop speed", "um/s", {1, 999999}},
    CommandInfo{CommandId::SetPitch, "pitch", Scope::Axis, "lead-screw pitch", "um/rev", {1, 999999}},
    CommandInfo{CommandId::SetSteps, "steps", Scope::Axis, "full steps per motor revolution", "steps/rev", {1, 10000}},
    CommandInfo{CommandId::SetMicrosteps, "usteps", Scope::Axis, "microsteps per full step (handler refuses non-powers of two)", "usteps", {1, 256}},
    CommandInfo{CommandId::SetIrun, "irun", Scope::Axis, "TMC2130 IHOLD_IRUN.IRUN current scale", "1/32", {0, 31}},
    CommandInfo{CommandId::SetIhold, "ihold", Scope::Axis, "TMC2130 IHOLD_IRUN.IHOLD current scale", "1/32", {0, 31}},
    CommandInfo{CommandId::PeriphOff, "sleep", Scope::Unit, "DummyData; peripherals off", "-", {0, 0}},
    CommandInfo{CommandId::PeriphOn, "wake", Scope::Unit, "DummyData; peripherals on", "-", {0, 0}},
    CommandInfo{CommandId::SaveParams, "save", Scope::Unit, "DummyData; write parameters to FRAM", "-", {0, 0}},
    CommandInfo{CommandId::ClearFault, "clear", Scope::Unit, "DummyData; leave the fault state", "-", {0, 0}},
    // The coordinated path (docs/cnc.md "On the board"): the X and Y parts of ONE frame form one
    // segment; an axis whose part carries something else keeps its last queued end.
    CommandInfo{CommandId::PathLine, "line", Scope::Axis, "absolute end of a coordinated line (path queue)", "um", {0, 999999}},
    CommandInfo{CommandId::PathCentre, "centre", Scope::Axis, "absolute centre of the next arc", "um", {0, 999999}},
    CommandInfo{CommandId::PathArcCw, "arc_cw", Scope::Axis, "absolute end of a clockwise arc (G2)", "um", {0, 999999}},
    CommandInfo{CommandId::PathArcCcw, "arc_ccw", Scope::Axis, "absolute end of a counter-clockwise arc (G3)", "um", {0, 999999}},
    CommandInfo{CommandId::PathEnd, "path_end", Scope::Unit, "DummyData; the last queued segment ends at rest", "-", {0, 0}},
    // Positioning at the slow speed level (thesis §7.7 and §8.2.2: two speed levels for manual
    // moves and positioning); goto and move run at the fast one (docs/protocol.md).
    CommandInfo{CommandId::GotoSlow, "goto_slow", Scope::Axis, "absolute target position, slow speed level", "um", {0, 999999}},
    CommandInfo{CommandId::MoveSlow, "move_slow", Scope::Axis, "relative move from the current position, slow speed level", "um", {-99999, 999999}},
};

inline constexpr std::size_t kCommandCount = kCommands.size();

constexpr const CommandInfo* find_command(std::uint32_t id) { return find_by_id(kCommands, id); }
constexpr const CommandInfo* find_command(std::string_view key) { return find_by_key(kCommands, key); }

constexpr const CommandInfo& info(CommandId id) { return kCommands[static_cast<std::size_t>(id)]; }

static_assert(dense<&CommandInfo::id>(kCommands), "command table is indexed by ID");
static_assert(kCommands.size() <= 100, "command IDs are two decimal digits");

}  // namespace ap::xy_codec
