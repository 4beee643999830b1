// The HC08 unit's firmware (core/hc08_board) against seed 002 §5.2 and docs/hc08.md "Menu",
// "Keypad", "Queue": key decoding, debounce, the queue's full policy, and a stateful test of
// the menu and display against the reference model (models/hc08).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/hc08_board/board.hpp"
#include "models/hc08/menu_model.hpp"

namespace {

namespace b = ap::hc08_board;
using ap::hc08_menu::Key;

// The kit's numbering SA1..SA12, three per row from the top left: the code is the driven
// column's bit (0x40, 0x20, 0x10) and the row lines PTD4..7 active low (seed 002 §5.2.3).
constexpr std::uint8_t kSet = 0x20 | 0x0D;    // SA5: column 1, row 1
constexpr std::uint8_t kLeft = 0x40 | 0x0D;   // SA4
constexpr std::uint8_t kRight = 0x10 | 0x0D;  // SA6
constexpr std::uint8_t kPlus = 0x20 | 0x0B;   // SA8: row 2
constexpr std::uint8_t kMinus = 0x20 | 0x0E;  // SA2: row 0
constexpr std::uint8_t kCodes[5] = {kSet, kLeft, kRight, kPlus, kMinus};

TEST(Hc08Keypad, TheFiveKeysAndNoOther) {
  EXPECT_EQ(b::decode(kSet), Key::Set);
  EXPECT_EQ(b::decode(kLeft), Key::Left);
  EXPECT_EQ(b::decode(kRight), Key::Right);
  EXPECT_EQ(b::decode(kPlus), Key::Plus);
  EXPECT_EQ(b::decode(kMinus), Key::Minus);
  int keys = 0;
  for (unsigned c = 0; c < 256; ++c) keys += b::decode(static_cast<std::uint8_t>(c)).has_value() ? 1 : 0;
  EXPECT_EQ(keys, 5);
  EXPECT_EQ(b::decode(0x40 | 0x0E), std::nullopt);  // SA1, unused
}

TEST(Hc08Keypad, BouncesMakeOnePressAndAHeldKeyNoMore) {
  b::Debouncer d;
  int presses = 0;
  const auto feed = [&](std::uint8_t code, int ms) {
    for (int i = 0; i < ms; ++i) presses += d.sample(code).has_value() ? 1 : 0;
  };
  for (int i = 0; i < 5; ++i) {  // 10 ms of bounce: on and off every ms
    feed(kSet, 1);
    feed(0, 1);
  }
  EXPECT_EQ(presses, 0);
  feed(kSet, 19);
  EXPECT_EQ(presses, 0);  // 19 stable samples are not yet 20
  feed(kSet, 1);
  EXPECT_EQ(presses, 1);
  feed(kSet, 500);  // held
  EXPECT_EQ(presses, 1);
  feed(0, 5);       // a short release is a bounce
  feed(kSet, 30);
  EXPECT_EQ(presses, 1);
  feed(0, 20);      // a real release
  feed(kSet, 20);
  EXPECT_EQ(presses, 2);
}

TEST(Hc08Queue, FullDropsTheNewKeyAndMotorMessagesTakeOneSlot) {
  b::Queue q;
  for (int i = 0; i < 1000; ++i) EXPECT_TRUE(q.push({b::Source::Motor, static_cast<std::uint16_t>(i)}));
  EXPECT_EQ(q.size(), 1);  // the latest angle only
  for (int i = 0; i < 7; ++i) EXPECT_TRUE(q.push({b::Source::Keyboard, kSet}));
  EXPECT_FALSE(q.push({b::Source::Keyboard, kPlus}));  // full: the new one is dropped [T]
  EXPECT_EQ(q.dropped(), 1U);
  EXPECT_TRUE(q.push({b::Source::Motor, 7}));  // the waiting angle is replaced
  const auto first = q.pop();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->src, b::Source::Motor);
  EXPECT_EQ(first->data, 7);
  int keys = 0;
  while (q.pop()) ++keys;
  EXPECT_EQ(keys, 7);
}

// Keys are never lost to the motor: any number of steps between keys, up to 7 keys waiting.
RC_GTEST_PROP(Hc08QueueProps, KeysAreNotLostToMotorMessages, ()) {
  b::Queue q;
  const auto ops = *rc::gen::container<std::vector<int>>(rc::gen::inRange(0, 3));
  int keys_in = 0, keys_out = 0;
  for (const int op : ops) {
    if (op == 0) {
      if (q.size() < 7) {
        RC_ASSERT(q.push({b::Source::Keyboard, kSet}));
        ++keys_in;
      }
    } else if (op == 1) {
      RC_ASSERT(q.push({b::Source::Motor, 1}));
    } else if (const auto m = q.pop()) {
      keys_out += m->src == b::Source::Keyboard ? 1 : 0;
    }
  }
  while (const auto m = q.pop()) keys_out += m->src == b::Source::Keyboard ? 1 : 0;
  RC_ASSERT(keys_in == keys_out);
  RC_ASSERT(q.dropped() == 0U);
}

TEST(Hc08Board, SetStartsModeBAndTheDisplayFollowsTheAngle) {
  b::Board u;
  EXPECT_EQ(u.display().indicator, 1);  // S_DEF, X1
  EXPECT_TRUE(u.display().k2);          // mode A at power-up [D]
  u.push_key(kMinus);                   // mode B [T Tab. 4.3]
  u.push_key(kSet);                     // start: 90° [D default]
  u.main_loop();
  EXPECT_TRUE(u.display().k3);
  ASSERT_TRUE(u.timer_running());
  int steps = 0;
  while (u.timer_running()) {
    u.timer_match();
    u.main_loop();
    ++steps;
  }
  EXPECT_EQ(steps, 10);  // 90° in 9° steps
  EXPECT_EQ(u.display().value, 900);
  EXPECT_EQ(u.display().point, 1);
}

TEST(Hc08Board, ASpeedTheDriveCannotMakeIsRefusedOnTheDisplay) {
  b::Board u;
  // To SET_SPEED, open the editor on 01.00, digit 1 up (02.00), digit 0 up twice: 22.00 rev/s,
  // past full step's 20.00. One key per main-loop pass: the queue holds 8.
  for (const std::uint8_t k : {kRight, kRight, kRight, kSet, kRight, kPlus, kLeft, kPlus, kPlus, kSet}) {
    u.push_key(k);
    u.main_loop();
  }
  EXPECT_TRUE(u.display().error);
  EXPECT_EQ(u.settings().speed_centi, 100);
  EXPECT_EQ(u.menu().state, ap::hc08_menu::State::Speed);
}

// The stateful test: any keys (the five and the others), timer steps and main-loop passes;
// after every key the menu state, the settings and the display are the model's.
RC_GTEST_PROP(Hc08BoardProps, MenuAndDisplayFollowTheModel, ()) {
  b::Board u;
  ap::model::hc08::MenuModel m;
  const auto n = *rc::gen::inRange(1, 120);
  for (int i = 0; i < n; ++i) {
    if (*rc::gen::inRange(0, 5) == 0) {
      const int k = *rc::gen::inRange(0, 300);
      for (int s = 0; s < k && u.timer_running(); ++s) u.timer_match();
      u.main_loop();
      continue;
    }
    const bool known = *rc::gen::inRange(0, 8) != 0;
    const int key = *rc::gen::inRange(0, 5);
    const std::uint8_t code = known ? kCodes[key] : *rc::gen::element<std::uint8_t>(0x4E, 0x1E, 0x4B, 0x1B, 0x47, 0x27, 0x17, 0x00, 0xFF);
    const bool running = u.timer_running();
    u.push_key(code);
    u.main_loop();
    if (known) m.press(key, running);
    static const char* const kName[] = {"S_DEF", "SET_DRIVE", "SET_DIRECT", "SET_SPEED", "SET_ANGLE", "SET_SPEEDx", "SET_ANGLEx"};
    RC_ASSERT(std::string(kName[static_cast<int>(u.menu().state)]) == m.state());
    RC_ASSERT(u.display().indicator == m.indicator());
    RC_ASSERT(static_cast<int>(u.display().value) == m.value(u.motor().angle_tenths()));
    RC_ASSERT(u.display().k2 == m.mode_a());
    RC_ASSERT((u.display().drive == '8') == m.half());
    RC_ASSERT((u.display().direction == 'r') == m.right());
    RC_ASSERT(u.settings().speed_centi == m.speed());
    RC_ASSERT(u.settings().angle_deg == m.angle());
    if (known) RC_ASSERT(u.display().error == m.error());
  }
}

}  // namespace
