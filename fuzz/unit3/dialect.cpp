// The `;` dialect's framer and parser on any bytes (docs/unit3.md "The wire"). Oracles: no
// crash or UB; every accepted line formats back to exactly the bytes it came from; a
// rejection names an error and a byte inside the line; a rejected parse writes nothing; the
// framer never holds more than one command's worth of bytes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "protocol/unit3/wire/dialect.hpp"

namespace {

namespace w = ap::unit3_wire;

void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> in(data, size);
  // The whole input as one line.
  w::Command sentinel;
  sentinel.kind = w::Kind::Move;
  sentinel.count = 4321;
  w::Command c = sentinel;
  const w::Rejection r = w::parse(in, c);
  if (r.ok()) {
    std::array<std::uint8_t, w::kMaxLine> out{};
    const std::size_t n = w::format(c, out);
    require(n == size);
    for (std::size_t i = 0; i < n; ++i) require(out[i] == data[i]);
  } else {
    require(c == sentinel);
    require(size == 0 || r.offset < size || r.error == w::Error::BadLength);
  }
  // The input as a stream.
  w::Framer f;
  std::uint32_t accepted = 0;
  for (std::size_t i = 0; i < size; ++i) {
    if (const auto e = f.push(data[i])) {
      require(e->stream_offset <= i);
      if (e->rejection.ok()) {
        ++accepted;
        std::array<std::uint8_t, w::kMaxLine> out{};
        const std::size_t n = w::format(e->command, out);
        require(n == i + 1 - e->stream_offset);
        for (std::size_t k = 0; k < n; ++k) require(out[k] == data[e->stream_offset + k]);
      } else {
        require(e->rejection.error != w::Error::None);
      }
    }
    require(f.pending() <= w::kMaxLine + 1);
  }
  require(f.counters().accepted == accepted);
  // Counter reports: what formats reads back, what reads back formats the same.
  if (size >= 9) {
    std::int64_t v = 0;
    for (std::size_t i = 1; i < 9; ++i) v = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) << 8U | data[i]);
    std::array<std::uint8_t, w::kReportLength> rep{};
    const auto axis = static_cast<w::Axis>(data[0] % 3U);
    if (w::format_report(axis, v, rep) != 0) {
      const auto back = w::parse_report(rep);
      require(back.has_value() && back->axis == axis && back->count == v);
    } else {
      require(v > w::kMaxReportCount || v < -w::kMaxReportCount);
    }
  }
  if (const auto rep = w::parse_report(in)) {
    std::array<std::uint8_t, w::kReportLength> out{};
    require(w::format_report(rep->axis, rep->count, out) == size);
    for (std::size_t i = 0; i < size; ++i) require(out[i] == data[i]);
  }
  return 0;
}
