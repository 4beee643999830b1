#pragma once
// The echo status table: an echo ID tells the PC both the axis status and how to read the
// data that follows it (the thesis's two jobs of an echo ID). Append; never renumber.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "protocol/xy/codec/id_table.hpp"
#include "protocol/xy/codec/range.hpp"

namespace ap::xy_codec {

enum class EchoStatus : std::uint8_t {
  Idle = 0,
  Accelerating = 1,
  ConstantSpeed = 2,
  Decelerating = 3,
  TargetReached = 4,
  StoppedByUser = 5,
  EndstopHit = 6,
  Homing = 7,
  BlockedCharger = 8,
  BlockedUsb = 9,
  BlockedBattery = 10,
  LinkLost = 11,
  Sleeping = 12,
  Fault = 13,
  FrameRejected = 14,
  CommandRefused = 15,
};

// FRAME_REJECTED data packs the reason and where it was found.
inline constexpr std::int32_t kRejectReasonScale = 100;

struct StatusInfo {
  EchoStatus id;
  std::string_view key;
  std::string_view meaning;
  std::string_view data;  // what the data field carries
  std::string_view unit;
  Range range;
};

inline constexpr Range kPositionRange{-99999, 999999};

// In flash on the Cortex-M4 (see kCommands in commands.hpp).
[[gnu::section(".rodata.ap.codec.statuses")]] inline constexpr std::array kStatuses = {
    StatusInfo{EchoStatus::Idle, "idle", "standing, no target", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::Accelerating, "accel", "moving, accelerating", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::ConstantSpeed, "const", "moving at constant speed", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::Decelerating, "decel", "moving, decelerating", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::TargetReached, "reached", "requested position reached", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::StoppedByUser, "stopped", "stopped by the user", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::EndstopHit, "endstop", "stopped by an endstop", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::Homing, "homing", "homing in progress", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::BlockedCharger, "blk_charger", "blocked: charger connected", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::BlockedUsb, "blk_usb", "blocked: USB connected", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::BlockedBattery, "blk_battery", "blocked: battery low", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::LinkLost, "link_lost", "stopped: command watchdog expired", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::Sleeping, "sleeping", "peripherals off", "position", "um", kPositionRange},
    StatusInfo{EchoStatus::Fault, "fault", "driver, storage or sensor fault", "fault code", "-", {0, 999999}},
    StatusInfo{EchoStatus::FrameRejected, "rejected", "last frame rejected", "reason*100 + byte offset", "-", {0, 99999}},
    StatusInfo{EchoStatus::CommandRefused, "refused", "command valid but refused in this state", "command ID", "-", {0, 99}},
};

inline constexpr std::size_t kStatusCount = kStatuses.size();

constexpr const StatusInfo* find_status(std::uint32_t id) { return find_by_id(kStatuses, id); }
constexpr const StatusInfo* find_status(std::string_view key) { return find_by_key(kStatuses, key); }

static_assert(dense<&StatusInfo::id>(kStatuses), "status table is indexed by ID");

}  // namespace ap::xy_codec
