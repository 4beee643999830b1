#include "core/unit3/settings/settings.hpp"

namespace ap::unit3_settings {

namespace {

constexpr std::size_t kCrcAt = kImageSize - 1;

bool in_range(const Settings& s) {
  for (std::size_t i = 0; i < kAxes; ++i) {
    if (s.mode[i] > kMaxMode || s.thread[i] > kMaxThread) return false;
  }
  return true;
}

}  // namespace

std::uint8_t crc8(std::span<const std::uint8_t> bytes) {
  std::uint8_t crc = 0;
  for (const std::uint8_t b : bytes) {
    crc = static_cast<std::uint8_t>(crc ^ b);
    for (int k = 0; k < 8; ++k) {
      const unsigned shifted = static_cast<unsigned>(crc) << 1U;
      crc = static_cast<std::uint8_t>((crc & 0x80U) != 0 ? shifted ^ 0x07U : shifted);
    }
  }
  return crc;
}

bool store(const Settings& s, std::span<std::uint8_t, kImageSize> image) {
  if (!in_range(s)) return false;
  image[0] = kVersion;
  for (std::size_t i = 0; i < kAxes; ++i) {
    image[1 + i] = s.mode[i];
    image[1 + kAxes + i] = s.thread[i];
  }
  image[kCrcAt] = crc8(image.first(kCrcAt));
  return true;
}

Loaded load(std::span<const std::uint8_t, kImageSize> image) {
  bool blank = true;
  for (const std::uint8_t b : image) blank = blank && b == 0xFF;
  if (blank) return {Load::Blank, kDefaults};
  if (crc8(image.first(kCrcAt)) != image[kCrcAt]) return {Load::BadChecksum, kDefaults};
  if (image[0] != kVersion) return {Load::BadVersion, kDefaults};
  Settings s;
  for (std::size_t i = 0; i < kAxes; ++i) {
    s.mode[i] = image[1 + i];
    s.thread[i] = image[1 + kAxes + i];
  }
  if (!in_range(s)) return {Load::BadValue, kDefaults};
  return {Load::Ok, s};
}

}  // namespace ap::unit3_settings
