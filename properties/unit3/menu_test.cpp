// The windows and buttons (core/unit3/menu) against seed 001 §3.7 and docs/unit3.md "The menu".
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

#include "core/unit3/menu/menu.hpp"

namespace {

namespace m = ap::unit3_menu;
using B = m::Button;
using ap::unit3_settings::Settings;

struct Rig {
  m::State s;
  Settings set{{0, 0, 0}, {4, 4, 4}};
  std::vector<m::Effect> effects;
  Rig& operator()(std::initializer_list<B> bs) {
    for (const B b : bs) effects.push_back(m::press(s, set, b));
    return *this;
  }
};

TEST(Unit3Menu, PowerUpShowsPositionsAndOnlyEnterLeavesIt) {
  Rig r;
  r({B::Back, B::Up, B::Down, B::Left, B::Right});
  EXPECT_EQ(r.s.window, m::Window::Positions);
  r({B::Enter});
  EXPECT_EQ(r.s.window, m::Window::Menu);
  r({B::Back});
  EXPECT_EQ(r.s.window, m::Window::Positions);  // [T] Back returns to the positions
}

TEST(Unit3Menu, StepSizeWindowLeftLargerRightSmallerSavedOnBack) {
  Rig r;
  r({B::Enter, B::Enter});  // MENU, first item: step size
  ASSERT_EQ(r.s.window, m::Window::StepSize);
  r({B::Right, B::Right, B::Right, B::Right, B::Right, B::Right});  // six presses: 1/32, saturated
  EXPECT_EQ(r.set.mode[0], 5);
  r({B::Left});  // larger step [T]
  EXPECT_EQ(r.set.mode[0], 4);
  r({B::Down, B::Down, B::Down, B::Right});  // axis Z (saturated at Z)
  EXPECT_EQ(r.set.mode[2], 1);
  EXPECT_EQ(r.set.mode[1], 0);
  r.effects.clear();
  r({B::Back});
  EXPECT_EQ(r.s.window, m::Window::Menu);
  ASSERT_EQ(r.effects.size(), 1U);
  EXPECT_EQ(r.effects[0], m::Effect::Save);
}

TEST(Unit3Menu, ThreadWindowRightNextThreadSaturatesAtM10) {
  Rig r;
  r({B::Enter, B::Down, B::Enter});
  ASSERT_EQ(r.s.window, m::Window::Thread);
  r({B::Down, B::Right, B::Right, B::Right});  // Y: M6 -> M8 -> M10 -> M10
  EXPECT_EQ(r.set.thread[1], 6);
  r({B::Up, B::Left, B::Left, B::Left, B::Left, B::Left});  // X: M6 down to M2
  EXPECT_EQ(r.set.thread[0], 0);
  EXPECT_EQ(m::press(r.s, r.set, B::Back), m::Effect::Save);
}

TEST(Unit3Menu, ZeroItemZeroesAndStaysInTheMenu) {
  Rig r;
  r({B::Enter, B::Down, B::Down, B::Down});  // saturates on the third item
  EXPECT_EQ(r.s.item, m::Item::Zero);
  EXPECT_EQ(m::press(r.s, r.set, B::Enter), m::Effect::Zero);
  EXPECT_EQ(r.s.window, m::Window::Menu);
}

// Any button sequence keeps every setting inside its table, and only Back from an editor
// saves (the thesis saves nowhere else).
RC_GTEST_PROP(Unit3MenuProps, SettingsStayInRangeAndOnlyBackFromAnEditorSaves, ()) {
  const auto presses = *rc::gen::container<std::vector<int>>(rc::gen::inRange(0, 6));
  m::State s;
  Settings set{{0, 0, 0}, {4, 4, 4}};
  for (const int p : presses) {
    const m::Window before = s.window;
    const m::Effect e = m::press(s, set, static_cast<B>(p));
    const bool editor = before == m::Window::StepSize || before == m::Window::Thread;
    RC_ASSERT((e == m::Effect::Save) == (editor && static_cast<B>(p) == B::Back));
    if (e == m::Effect::Zero) RC_ASSERT(before == m::Window::Menu && s.item == m::Item::Zero);
    for (int a = 0; a < 3; ++a) {
      RC_ASSERT(set.mode[static_cast<std::size_t>(a)] <= 5);
      RC_ASSERT(set.thread[static_cast<std::size_t>(a)] <= 6);
    }
    RC_ASSERT(s.axis < 3);
  }
}

}  // namespace
