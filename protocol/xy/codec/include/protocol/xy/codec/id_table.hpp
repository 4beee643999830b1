#pragma once
// The lookups every ID table of the wire contract needs (commands, statuses, subscribers,
// rejection reasons), written once. The tables are indexed by ID (docs/protocol.md "ID
// tables": IDs are dense and never renumbered), which `dense` proves at compile time, so a
// lookup by ID is a bounds-checked index.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ap::xy_codec {

// The entry with this ID, or nullptr outside the table.
template <typename Info, std::size_t N>
constexpr const Info* find_by_id(const std::array<Info, N>& table, std::uint32_t id) {
  return id < N ? &table[id] : nullptr;
}

// The entry with this key, or nullptr.
template <typename Info, std::size_t N>
constexpr const Info* find_by_key(const std::array<Info, N>& table, std::string_view key) {
  for (const Info& e : table) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

// Entry i has ID i (`IdField` names the entry's ID member).
template <auto IdField, typename Info, std::size_t N>
constexpr bool dense(const std::array<Info, N>& table) {
  for (std::size_t i = 0; i < N; ++i) {
    if (static_cast<std::size_t>(table[i].*IdField) != i) return false;
  }
  return true;
}

}  // namespace ap::xy_codec
