#pragma once
// Human-readable views of the register table and of captured datagrams, shared by
// `axisproof regs`, docs/tmc2130.md and the test that keeps the two equal.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/xy/tmc2130/datagram.hpp"

namespace ap::model::xy_tmc2130 {

enum class MapFormat { Text, Csv, Markdown };

std::string register_map(MapFormat format);

// Decodes a MOSI datagram (a request) or, with `as_reply`, a MISO datagram (status + data;
// the data belongs to the previous access, so `reg` names it when known).
std::string decode_datagram(const ap::xy_tmc2130::Datagram& d, bool as_reply,
                            std::optional<std::uint8_t> reg = std::nullopt);

// Parses "90 00 07 0C 03", "0x90,0x00,..." or "9000070C03"; nullopt unless exactly 5 bytes.
std::optional<ap::xy_tmc2130::Datagram> parse_datagram(const std::vector<std::string>& words);

}  // namespace ap::model::xy_tmc2130
