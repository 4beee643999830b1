// The HC08 unit's firmware (core/hc08/board) against seed 002 §5.2 and docs/hc08.md "Menu",
// "Keypad", "Queue": key decoding, debounce, the queue's full policy, and a stateful test of
// the menu and display against the reference model (models/hc08).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "core/hc08/board/board.hpp"
#include "models/hc08/angle_model.hpp"
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

// docs/hc08.md "Power-up": S_DEF (002_*.txt:737); mode A, four-step, right, 1.00 rev/s, 90° [D];
// the coils of phases 1 and 2 on, PTA3 and PTA4 (Tab. 4.1): port 0x18 [D]; the angle shown 0.0.
TEST(Hc08Board, PowerUpIsTheDocumentedState) {
  const b::Board u;
  EXPECT_EQ(u.menu().state, ap::hc08_menu::State::Def);
  EXPECT_EQ(u.settings().mode, ap::hc08_motor::Mode::A);
  EXPECT_EQ(u.settings().drive, ap::hc08_drive::Drive::Full);
  EXPECT_TRUE(u.settings().right);
  EXPECT_EQ(u.settings().speed_centi, 100);
  EXPECT_EQ(u.settings().angle_deg, 90);
  EXPECT_FALSE(u.timer_running());
  EXPECT_EQ(u.port(), 0x18);
  const b::Display want{1, true, false, 'r', '4', 0, 1, false, false};
  EXPECT_EQ(u.display(), want);
}

// At rest the coils of the last step stay energised and hold the rotor: a stepper "holds its
// angle in every position, so it needs power at rest too" (002_*.txt:211, 231; "at every moment
// at least one phase is on", 215). docs/hc08.md "Power-up".
TEST(Hc08Board, TheCoilsHoldTheLastStepAtRest) {
  b::Board u;
  u.push_key(kMinus);  // mode B
  u.push_key(kSet);    // 90°: 10 full steps from 0x18 (docs/hc08.md "Excitation"): 0x30 0x60 0x48 0x18 ...
  u.main_loop();
  std::vector<std::uint8_t> ports;
  while (u.timer_running()) {
    u.timer_match();
    u.main_loop();
    ports.push_back(u.port());
  }
  ASSERT_EQ(ports.size(), 10U);
  EXPECT_EQ(ports.back(), 0x60);  // index 10 mod 4 = 2: phases 3 and 4
  for (int i = 0; i < 1000; ++i) {
    EXPECT_FALSE(u.timer_match());  // a stray match moves nothing
    u.main_loop();
    EXPECT_EQ(u.port(), 0x60);
  }
  u.push_key(kRight);  // keys that start nothing leave the coils as they are
  u.push_key(0x4E);
  u.main_loop();
  EXPECT_EQ(u.port(), 0x60);
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

// The thesis checks the user's inputs and adjusts them to the motor (002_*.txt:729; docs/hc08.md
// "Menu"): a speed outside 0.02 .. 20.00 rev/s in full step (800 Hz / 40 steps [T Tab. 3.1]) or
// 0.01 .. 21.25 in half step (1700 Hz / 80) becomes the nearer end, with the adjusted mark.
TEST(Hc08Board, ASpeedTheMotorCannotMakeIsAdjustedIntoItsRange) {
  b::Board u;
  const auto keys = [&](std::initializer_list<std::uint8_t> ks) {
    for (const std::uint8_t k : ks) {  // one key per main-loop pass: the queue holds 8
      u.push_key(k);
      u.main_loop();
    }
  };
  // To SET_SPEED, open the editor on 01.00, digit 1 up (02.00), digit 0 up twice: 22.00 rev/s,
  // 880 Hz in full step: 20.00.
  keys({kRight, kRight, kRight, kSet, kRight, kPlus, kLeft, kPlus, kPlus});
  EXPECT_EQ(u.display().value, 2200);
  EXPECT_FALSE(u.display().adjusted);
  keys({kSet});
  EXPECT_EQ(u.settings().speed_centi, 2000);
  EXPECT_TRUE(u.display().adjusted);
  EXPECT_FALSE(u.display().error);
  EXPECT_EQ(u.menu().state, ap::hc08_menu::State::Speed);
  EXPECT_EQ(u.display().value, 2000);
  keys({kLeft});  // the mark lasts until the next key
  EXPECT_FALSE(u.display().adjusted);
  // 00.00 in full step: the timer cannot count it, nor 0.01 (6 144 000 ticks past 64 x 65 536):
  // 0.02 rev/s.
  keys({kRight, kSet, kMinus, kMinus});  // SET_SPEED again, digit 0: 20.00 -> 10.00 -> 00.00
  EXPECT_EQ(u.display().value, 0);
  keys({kSet});
  EXPECT_EQ(u.settings().speed_centi, 2);
  EXPECT_TRUE(u.display().adjusted);
  // 21.25 in half step is the maximum; to full step it becomes 20.00.
  keys({kLeft, kLeft, kPlus});  // SET_DRIVE, eight-step: 0.02 is made, nothing adjusted
  EXPECT_EQ(u.settings().drive, ap::hc08_drive::Drive::Half);
  EXPECT_EQ(u.settings().speed_centi, 2);
  EXPECT_FALSE(u.display().adjusted);
  // SET_SPEED, the editor on 00.02: digit 0 +2, digit 1 +1, digit 2 +2, digit 3 +3: 21.25.
  keys({kRight, kRight, kSet, kPlus, kPlus, kRight, kPlus, kRight, kPlus, kPlus, kRight, kPlus, kPlus, kPlus});
  EXPECT_EQ(u.display().value, 2125);
  keys({kSet});
  EXPECT_EQ(u.settings().speed_centi, 2125);  // 21.25 exactly: 1700 Hz
  EXPECT_FALSE(u.display().adjusted);
  keys({kLeft, kLeft, kMinus});  // SET_DRIVE, four-step: 850 Hz is past 800
  EXPECT_EQ(u.settings().drive, ap::hc08_drive::Drive::Full);
  EXPECT_EQ(u.settings().speed_centi, 2000);
  EXPECT_TRUE(u.display().adjusted);
  EXPECT_EQ(u.display().value, 2000);
}

// The stateful test: any keys (the five and the others), timer steps and main-loop passes;
// after every key the menu state, the settings and the display are the model's, the angle
// shown being where the coils put the rotor (models/hc08/angle_model.hpp: read from every
// pattern the port takes, not from the motor's count; docs/hc08.md "Angle arithmetic").
RC_GTEST_PROP(Hc08BoardProps, MenuAndDisplayFollowTheModel, ()) {
  b::Board u;
  ap::model::hc08::MenuModel m;
  ap::model::hc08::CoilTracker coils;
  const auto n = *rc::gen::inRange(1, 120);
  for (int i = 0; i < n; ++i) {
    if (*rc::gen::inRange(0, 5) == 0) {
      const int k = *rc::gen::inRange(0, 300);
      for (int s = 0; s < k && u.timer_running(); ++s) {
        u.timer_match();
        coils.feed(u.port());
      }
      u.main_loop();
      continue;
    }
    const bool known = *rc::gen::inRange(0, 8) != 0;
    const int key = *rc::gen::inRange(0, 5);
    const std::uint8_t code = known ? kCodes[key] : *rc::gen::element<std::uint8_t>(0x4E, 0x1E, 0x4B, 0x1B, 0x47, 0x27, 0x17, 0x00, 0xFF);
    const bool running = u.timer_running();
    u.push_key(code);
    u.main_loop();
    coils.feed(u.port());  // a drive change at rest moves the coils without a step
    if (known) m.press(key, running);
    static const char* const kName[] = {"S_DEF", "SET_DRIVE", "SET_DIRECT", "SET_SPEED", "SET_ANGLE", "SET_SPEEDx", "SET_ANGLEx"};
    RC_ASSERT(std::string(kName[static_cast<int>(u.menu().state)]) == m.state());
    RC_ASSERT(u.display().indicator == m.indicator());
    RC_ASSERT(coils.ok());
    RC_ASSERT(static_cast<int>(u.display().value) == m.value(coils.angle_tenths()));
    RC_ASSERT(u.display().k2 == m.mode_a());
    RC_ASSERT((u.display().drive == '8') == m.half());
    RC_ASSERT((u.display().direction == 'r') == m.right());
    RC_ASSERT(u.settings().speed_centi == m.speed());
    RC_ASSERT(u.settings().angle_deg == m.angle());
    if (known) RC_ASSERT(u.display().error == m.error());
    if (known) RC_ASSERT(u.display().adjusted == m.adjusted());
  }
}

}  // namespace
