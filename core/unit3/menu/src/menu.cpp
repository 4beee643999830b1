#include "core/unit3/menu/menu.hpp"

namespace ap::unit3_menu {

namespace {

std::uint8_t up_to(std::uint8_t v, std::uint8_t max) { return v < max ? static_cast<std::uint8_t>(v + 1) : max; }
std::uint8_t down(std::uint8_t v) { return v > 0 ? static_cast<std::uint8_t>(v - 1) : 0; }

Effect in_menu(State& s, Button b) {
  const auto item = static_cast<std::uint8_t>(s.item);
  switch (b) {
    case Button::Up: s.item = static_cast<Item>(down(item)); return Effect::None;
    case Button::Down: s.item = static_cast<Item>(up_to(item, kItems - 1)); return Effect::None;
    case Button::Back: s.window = Window::Positions; return Effect::None;
    case Button::Enter:
      if (s.item == Item::Zero) return Effect::Zero;  // stays in the menu [D]
      s.window = s.item == Item::StepSize ? Window::StepSize : Window::Thread;
      s.axis = 0;
      return Effect::None;
    case Button::Left:
    case Button::Right: return Effect::None;
  }
  return Effect::None;
}

Effect in_editor(State& s, unit3_settings::Settings& settings, Button b) {
  if (s.axis >= unit3_settings::kAxes) s.axis = 0;  // a state no press makes; never an index past the table
  const bool steps = s.window == Window::StepSize;
  auto& value = steps ? settings.mode[s.axis] : settings.thread[s.axis];
  const std::uint8_t max = steps ? unit3_settings::kMaxMode : unit3_settings::kMaxThread;
  switch (b) {
    case Button::Up: s.axis = down(s.axis); return Effect::None;
    case Button::Down: s.axis = up_to(s.axis, unit3_settings::kAxes - 1); return Effect::None;
    case Button::Left: value = down(value); return Effect::None;
    case Button::Right: value = up_to(value, max); return Effect::None;
    case Button::Back: s.window = Window::Menu; return Effect::Save;
    case Button::Enter: return Effect::None;
  }
  return Effect::None;
}

}  // namespace

Effect press(State& s, unit3_settings::Settings& settings, Button b) {
  switch (s.window) {
    case Window::Positions:
      if (b == Button::Enter) {
        s.window = Window::Menu;
        s.item = Item::StepSize;
      }
      return Effect::None;
    case Window::Menu: return in_menu(s, b);
    case Window::StepSize:
    case Window::Thread: return in_editor(s, settings, b);
  }
  return Effect::None;
}

}  // namespace ap::unit3_menu
