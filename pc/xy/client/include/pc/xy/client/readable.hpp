#pragma once
// The readable form used by `axisproof frame encode` and the golden vectors:
//   seq=5 x=jog:+:fast y=goto:20000 sub=battery sub=encoder:1
// x/y take a command key from codec/commands.hpp and an optional ":data" (default 0, the
// DummyData); jog also takes ":+|-:fast|slow". sub takes a subscriber key and ":arg".
#include <string>
#include <string_view>

#include "core/xy/frame/frames.hpp"

namespace ap::xy_client {

// Empty string on success, otherwise what was wrong (out untouched).
std::string parse_readable(std::string_view text, xy_frame::CommandFrame& out);
// The canonical readable form, which parse_readable accepts back.
std::string to_readable(const xy_frame::CommandFrame& f);
// Multi-line field-by-field descriptions (decode output).
std::string describe(const xy_frame::CommandFrame& f);
std::string describe(const xy_frame::EchoFrame& f);
std::string describe(const xy_frame::Rejection& r);

}  // namespace ap::xy_client
