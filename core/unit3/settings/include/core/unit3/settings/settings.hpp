#pragma once
// The unit's EEPROM settings (seed 001 §3.8, docs/unit3.md "Settings"): the step mode and the
// thread of each axis, written when the menu saves them and read at power-up and on `G;`.
// The thesis stores them bare; here they carry a version byte and a CRC-8, so a torn write or
// a never-written EEPROM (all 0xFF) is told from a setting [D].
#include <array>
#include <cstdint>
#include <span>

namespace ap::unit3_settings {

inline constexpr std::size_t kAxes = 3;
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kImageSize = 8;  // version, 3 modes, 3 threads, CRC-8
inline constexpr std::uint8_t kMaxMode = 5;    // 1/32 step [T]
inline constexpr std::uint8_t kMaxThread = 6;  // M10 [T]

struct Settings {
  std::array<std::uint8_t, kAxes> mode{};    // 0..5
  std::array<std::uint8_t, kAxes> thread{};  // 0..6
  friend constexpr bool operator==(const Settings&, const Settings&) = default;
};

// Power-up without valid settings [D]: full step (the DRV8825's MODE pins default, all low)
// and M6 (1 mm per revolution, one of the thesis's two stated pitches), which is thread digit 4
// by the table's decided order (core/unit3/axis, kThreadTable).
inline constexpr Settings kDefaults{{0, 0, 0}, {4, 4, 4}};

enum class Load : std::uint8_t {
  Ok = 0,
  Blank,        // never written: every byte 0xFF
  BadChecksum,  // the CRC does not match (a torn or decayed write)
  BadVersion,   // written by another layout
  BadValue,     // intact, but a mode or thread past its table
};

struct Loaded {
  Load status = Load::Ok;
  Settings settings{};  // the stored ones when Ok, else kDefaults
};

// CRC-8, polynomial x^8 + x^2 + x + 1 (0x07), initial value 0, over bytes [0, 7).
std::uint8_t crc8(std::span<const std::uint8_t> bytes);

// The image to write; the settings must be in range (false and nothing written otherwise).
bool store(const Settings& s, std::span<std::uint8_t, kImageSize> image);
Loaded load(std::span<const std::uint8_t, kImageSize> image);

}  // namespace ap::unit3_settings
