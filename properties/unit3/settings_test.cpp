// EEPROM settings (core/unit3/settings, docs/unit3.md "Settings"): what is stored loads back,
// a blank or damaged image loads the documented defaults and says why.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>

#include "core/unit3/settings/settings.hpp"

namespace {

namespace s = ap::unit3_settings;
using Image = std::array<std::uint8_t, s::kImageSize>;

// CRC-8/0x07 of "123456789" is 0xF4 (the catalogue's check value for CRC-8, init 0).
TEST(Unit3Settings, Crc8CheckValue) {
  const std::array<std::uint8_t, 9> digits{'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(s::crc8(digits), 0xF4);
}

TEST(Unit3Settings, BlankAndDamagedImagesLoadTheDefaults) {
  Image blank;
  blank.fill(0xFF);
  EXPECT_EQ(s::load(blank).status, s::Load::Blank);
  EXPECT_EQ(s::load(blank).settings, (s::Settings{{0, 0, 0}, {4, 4, 4}}));  // full step, M6 [D]
  Image img{};
  ASSERT_TRUE(s::store({{5, 0, 3}, {0, 6, 4}}, img));
  EXPECT_EQ(img, (Image{1, 5, 0, 3, 0, 6, 4, s::crc8(std::span<const std::uint8_t>(img.data(), 7))}));
  Image other = img;
  other[0] = 2;  // another layout, checksum made to match
  other[7] = s::crc8(std::span<const std::uint8_t>(other.data(), 7));
  EXPECT_EQ(s::load(other).status, s::Load::BadVersion);
  Image wrong = img;
  wrong[1] = 6;  // mode 6: no such DRV8825 step
  wrong[7] = s::crc8(std::span<const std::uint8_t>(wrong.data(), 7));
  EXPECT_EQ(s::load(wrong).status, s::Load::BadValue);
  EXPECT_EQ(s::load(wrong).settings, s::kDefaults);
  EXPECT_FALSE(s::store({{0, 0, 6}, {0, 0, 0}}, img));
  EXPECT_FALSE(s::store({{0, 0, 0}, {7, 0, 0}}, img));
}

RC_GTEST_PROP(Unit3SettingsProps, StoredSettingsLoadBackAndEveryBitFlipIsCaught, ()) {
  s::Settings in;
  for (auto& m : in.mode) m = *rc::gen::inRange<std::uint8_t>(0, s::kMaxMode + 1);
  for (auto& t : in.thread) t = *rc::gen::inRange<std::uint8_t>(0, s::kMaxThread + 1);
  Image img{};
  RC_ASSERT(s::store(in, img));
  const auto back = s::load(img);
  RC_ASSERT(back.status == s::Load::Ok);
  RC_ASSERT(back.settings == in);
  for (std::size_t bit = 0; bit < img.size() * 8; ++bit) {
    Image flipped = img;
    flipped[bit / 8] = static_cast<std::uint8_t>(flipped[bit / 8] ^ (1U << (bit % 8)));
    const auto got = s::load(flipped);
    RC_ASSERT(got.status == s::Load::BadChecksum);
    RC_ASSERT(got.settings == s::kDefaults);
  }
}

}  // namespace
