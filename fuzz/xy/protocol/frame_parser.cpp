// Parser fuzz target. Oracles: no crash or UB; a rejected input leaves the output untouched;
// an accepted input formats back to exactly the same bytes (format(parse(b)) == b).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>

#include "protocol/xy/codec/layout.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/frame/echo_codec.hpp"
#include "crc_repair.hpp"

namespace {

template <class Frame, std::size_t N, class Parse, class Format>
void check(std::span<const std::uint8_t> in, Parse parse, Format format) {
  static_assert(std::is_trivially_copyable_v<Frame>);
  // Byte images, padding included (memset), so "untouched" is one memcmp rather than an
  // instrumented field-by-field operator== on every input.
  Frame out;
  std::memset(static_cast<void*>(&out), 0xA5, sizeof out);
  out.seq = 4321;  // impossible value: shows whether a rejected parse wrote anything
  unsigned char sentinel[sizeof(Frame)];
  std::memcpy(sentinel, &out, sizeof out);
  const auto r = parse(in, out);
  if (!r.ok()) {
    ap::fuzz::require(std::memcmp(&out, sentinel, sizeof out) == 0);
    ap::fuzz::require(r.offset <= N);
    return;
  }
  std::array<std::uint8_t, N> again{};
  ap::fuzz::require(format(out, again).ok());
  ap::fuzz::require(in.size() == N && std::memcmp(in.data(), again.data(), N) == 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);
  check<ap::xy_frame::CommandFrame, ap::xy_codec::kCommandLength>(in, ap::xy_frame::parse_command, ap::xy_frame::format_command);
  check<ap::xy_frame::EchoFrame, ap::xy_codec::kEchoLength>(in, ap::xy_frame::parse_echo, ap::xy_frame::format_echo);
  return 0;
}
