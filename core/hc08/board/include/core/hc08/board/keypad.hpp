#pragma once
// The kit's 3x4 keypad (seed 002 §3.2, §5.2.3; docs/hc08.md "Keypad"): one column driven low at
// a time (PTC6, PTC5, PTC4), the rows read on PTD7..4 active low. A key's code is the column bit
// in the high nibble and the row nibble in the low one [T: KBI_Keypressed]. Five keys are used,
// in a diamond with SET in the centre [T Tab. 4.2]: SA2, SA4, SA5, SA6, SA8 on the kit's
// numbering (row-major from the top left, 3 per row) [D: the schematic is not in the text].
#include <cstdint>
#include <optional>

#include "core/hc08/menu/menu.hpp"

namespace ap::hc08_board {

// The code of key SA<n> (n = 1..12): column (n - 1) % 3 -> bit 0x40 >> col, row (n - 1) / 3.
constexpr std::uint8_t key_code(unsigned n) {
  const unsigned col = (n - 1U) % 3U, row = (n - 1U) / 3U;
  return static_cast<std::uint8_t>((0x40U >> col) | (0x0FU & ~(1U << row)));
}

// The five keys [T Tab. 4.2]: SET SA5, LEFT SA4, RIGHT SA6, PLUS SA8, MINUS SA2.
std::optional<hc08_menu::Key> decode(std::uint8_t code);

// Debounce (the thesis's Flasback_delay): the row lines must read the same for kStable
// consecutive samples, one per millisecond, before a press counts [D: "several tens" of reads,
// bounce lasting "a few to tens of ms" T §4.2.1]. A press is reported once, when it has become
// stable; a release must be stable as long before the next press counts.
class Debouncer {
 public:
  static constexpr std::uint8_t kStable = 20;
  // One sample: the key code the scan sees now (0 when no key is down). Returns a code once
  // per stable press.
  std::optional<std::uint8_t> sample(std::uint8_t code);

 private:
  std::uint8_t last_ = 0;
  std::uint8_t count_ = 0;
  std::uint8_t reported_ = 0;  // the stable state last acted on
};

}  // namespace ap::hc08_board
