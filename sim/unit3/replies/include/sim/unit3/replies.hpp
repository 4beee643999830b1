#pragma once
// What the PC reads from the unit (docs/unit3.md "Replies"), for the unit3 tests and fuzz
// targets: every byte the unit's UART has queued, and that text cut after each ';'. A fixture
// over the unit's firmware (core/unit3/board), shared by the property tests (properties/unit3)
// and the fuzz target (fuzz/unit3) so both read the replies the same way.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/unit3/board/unit.hpp"

namespace ap::sim::unit3 {

inline std::string take_all(ap::unit3_board::Unit& u) {
  std::string s;
  std::array<std::uint8_t, 64> buf{};
  while (const std::size_t n = u.take_tx(buf)) s.append(buf.begin(), buf.begin() + static_cast<long>(n));
  return s;
}

// The replies in `rx`, each ending with ';'; bytes after the last ';' go to `rest`.
inline std::vector<std::string> split_replies(const std::string& rx, std::string* rest = nullptr) {
  std::vector<std::string> v;
  std::string cur;
  for (const char c : rx) {
    cur += c;
    if (c == ';') {
      v.push_back(cur);
      cur.clear();
    }
  }
  if (rest != nullptr) *rest = cur;
  return v;
}

}  // namespace ap::sim::unit3
