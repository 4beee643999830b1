#pragma once
// Echo frame parser and formatter; same rules as the command codec (command_codec.hpp).
#include <cstdint>
#include <span>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/frames.hpp"

namespace ap::xy_frame {

using EchoBytes = std::span<std::uint8_t, xy_codec::kEchoLength>;

Rejection parse_echo(std::span<const std::uint8_t> bytes, EchoFrame& out);
Rejection validate(const EchoFrame& frame);
Rejection format_echo(const EchoFrame& frame, EchoBytes out);

}  // namespace ap::xy_frame
