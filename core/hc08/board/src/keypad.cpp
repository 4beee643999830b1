#include "core/hc08/board/keypad.hpp"

namespace ap::hc08_board {

static_assert(key_code(5) == 0x2D);  // SET: column 1 (0x20), row 1 (0b1101)
static_assert(key_code(2) == 0x2E);

std::optional<hc08_menu::Key> decode(std::uint8_t code) {
  using K = hc08_menu::Key;
  switch (code) {
    case key_code(5): return K::Set;
    case key_code(4): return K::Left;
    case key_code(6): return K::Right;
    case key_code(8): return K::Plus;
    case key_code(2): return K::Minus;
    default: return std::nullopt;  // the other seven keys and any code a scan cannot give
  }
}

std::optional<std::uint8_t> Debouncer::sample(std::uint8_t code) {
  if (code != last_) {
    last_ = code;
    count_ = 1;
    return std::nullopt;
  }
  if (count_ < kStable) ++count_;
  if (count_ < kStable || code == reported_) return std::nullopt;
  reported_ = code;
  if (code == 0) return std::nullopt;  // a stable release
  return code;
}

}  // namespace ap::hc08_board
