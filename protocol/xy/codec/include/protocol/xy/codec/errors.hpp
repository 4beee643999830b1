#pragma once
// Why a frame was rejected. The numeric values travel on the wire (the data of a
// FRAME_REJECTED echo is reason * 100 + byte offset), so they are fixed: append, never renumber.
#include <array>
#include <cstdint>
#include <string_view>

#include "protocol/xy/codec/id_table.hpp"

namespace ap::xy_codec {

enum class FrameError : std::uint8_t {
  None = 0,
  BadStart = 1,            // first byte is not the start character
  BadLength = 2,           // frame cut short: end or a new start character came early
  BadChar = 3,             // a byte not allowed at its position (incl. "-00000", lower-case hex)
  BadCrc = 4,              // CRC field does not match the payload
  BadEnd = 5,              // last byte is not the end character
  UnknownCommand = 6,      // command ID not in the table
  UnknownSubscriber = 7,   // subscriber ID not in the table
  UnknownStatus = 8,       // echo status ID not in the table
  DataOutOfRange = 9,      // data outside the ID's allowed range
  ArgOutOfRange = 10,      // subscriber argument outside its allowed range
  Unhandled = 11,          // valid frame, but no handler is installed for a command ID
};

struct FrameErrorInfo {
  FrameError error;
  std::string_view key;
  std::string_view meaning;
};

inline constexpr std::array kFrameErrors = {
    FrameErrorInfo{FrameError::None, "none", "no error"},
    FrameErrorInfo{FrameError::BadStart, "bad_start", "first byte is not the start character"},
    FrameErrorInfo{FrameError::BadLength, "bad_length", "frame cut short (end or start character too early)"},
    FrameErrorInfo{FrameError::BadChar, "bad_char", "character not allowed at this position"},
    FrameErrorInfo{FrameError::BadCrc, "bad_crc", "CRC-16 does not match the payload"},
    FrameErrorInfo{FrameError::BadEnd, "bad_end", "last byte is not the end character"},
    FrameErrorInfo{FrameError::UnknownCommand, "unknown_command", "command ID not in the table"},
    FrameErrorInfo{FrameError::UnknownSubscriber, "unknown_subscriber", "subscriber ID not in the table"},
    FrameErrorInfo{FrameError::UnknownStatus, "unknown_status", "echo status ID not in the table"},
    FrameErrorInfo{FrameError::DataOutOfRange, "data_out_of_range", "data outside the ID's range"},
    FrameErrorInfo{FrameError::ArgOutOfRange, "arg_out_of_range", "subscriber argument outside its range"},
    FrameErrorInfo{FrameError::Unhandled, "unhandled", "no handler installed for the command ID"},
};

constexpr std::string_view error_key(FrameError e) {
  const FrameErrorInfo* i = find_by_id(kFrameErrors, static_cast<std::uint32_t>(e));
  return i != nullptr ? i->key : std::string_view{"?"};
}

static_assert(dense<&FrameErrorInfo::error>(kFrameErrors), "kFrameErrors is indexed by FrameError");

}  // namespace ap::xy_codec
