#pragma once
// The subscriber table. A command carries kSubscriberSlots (ID, argument) slots; the echo
// copies each slot and appends its data. ID 0 marks an empty slot, so an echo always has
// the same length whatever was requested (G21). Append; never renumber.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "protocol/xy/codec/id_table.hpp"
#include "protocol/xy/codec/range.hpp"

namespace ap::xy_codec {

enum class SubscriberId : std::uint8_t {
  None = 0,
  BatteryMv = 1,
  ChargeMa = 2,
  TemperatureMc = 3,
  RotationMdeg = 4,
  EncoderUm = 5,
  DrvStatusLo = 6,
  DrvStatusHi = 7,
  Param = 8,
  LinkStats = 9,
};

// LinkStats argument: which counter (values wrap modulo 1 000 000).
enum class LinkStat : std::uint8_t { AcceptedFrames = 0, RejectedFrames = 1, RejectedBytes = 2, WatchdogExpiries = 3 };

struct SubscriberInfo {
  SubscriberId id;
  std::string_view key;
  std::string_view meaning;
  std::string_view arg;   // what the argument selects
  Range arg_range;
  std::string_view unit;
  Range range;            // data range in the echo
};

// In flash on the Cortex-M4 (see kCommands in commands.hpp).
[[gnu::section(".rodata.ap.codec.subscribers")]] inline constexpr std::array kSubscribers = {
    SubscriberInfo{SubscriberId::None, "none", "empty slot", "-", {0, 0}, "-", {0, 0}},
    SubscriberInfo{SubscriberId::BatteryMv, "battery", "battery voltage", "-", {0, 0}, "mV", {0, 99999}},
    SubscriberInfo{SubscriberId::ChargeMa, "charge", "charge current (negative = discharge)", "-", {0, 0}, "mA", {-99999, 99999}},
    SubscriberInfo{SubscriberId::TemperatureMc, "temp", "board temperature", "-", {0, 0}, "m degC", {-99999, 999999}},
    SubscriberInfo{SubscriberId::RotationMdeg, "rotation", "platform rotation from the IMU", "-", {0, 0}, "m deg", {0, 359999}},
    SubscriberInfo{SubscriberId::EncoderUm, "encoder", "absolute encoder position", "axis 0=X 1=Y", {0, 1}, "um", {-99999, 999999}},
    SubscriberInfo{SubscriberId::DrvStatusLo, "drv_lo", "TMC2130 DRV_STATUS bits 15..0", "axis 0=X 1=Y", {0, 1}, "raw", {0, 65535}},
    SubscriberInfo{SubscriberId::DrvStatusHi, "drv_hi", "TMC2130 DRV_STATUS bits 31..16", "axis 0=X 1=Y", {0, 1}, "raw", {0, 65535}},
    SubscriberInfo{SubscriberId::Param, "param", "one stored (FRAM) parameter", "parameter index", {0, 99}, "as stored", {-99999, 999999}},
    SubscriberInfo{SubscriberId::LinkStats, "link", "link statistics counter", "0 accepted, 1 rejected frames, 2 rejected bytes, 3 watchdog expiries", {0, 3}, "count mod 10^6", {0, 999999}},
};

inline constexpr std::size_t kSubscriberCount = kSubscribers.size();

constexpr const SubscriberInfo* find_subscriber(std::uint32_t id) { return find_by_id(kSubscribers, id); }
constexpr const SubscriberInfo* find_subscriber(std::string_view key) { return find_by_key(kSubscribers, key); }

static_assert(dense<&SubscriberInfo::id>(kSubscribers), "subscriber table is indexed by ID");

}  // namespace ap::xy_codec
