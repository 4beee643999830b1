#include "models/hc08/menu_model.hpp"

namespace ap::model::hc08 {

// The speeds the motor makes (docs/hc08.md "Timer"): 0.02 .. 20.00 rev/s full step, 0.01 ..
// 21.25 half step; a speed outside is set to the nearer end (docs/hc08.md "Menu").
int MenuModel::fit(int centi, bool half) {
  const int lo = half ? 1 : 2, hi = half ? 2125 : 2000;
  const int v = centi < lo ? lo : centi > hi ? hi : centi;
  adjusted_ = v != centi;
  return v;
}

std::string MenuModel::press(int key, bool running) {
  enum { Set, Left, Right, Plus, Minus };
  error_ = false;
  adjusted_ = false;
  if (state_ >= 5) {  // editing a digit
    switch (key) {
      case Left: digit_ = digit_ > 0 ? digit_ - 1 : 0; return "";
      case Right: digit_ = digit_ < 3 ? digit_ + 1 : 3; return "";
      case Plus: edit_[digit_] = (edit_[digit_] + 1) % 10; return "";
      case Minus: edit_[digit_] = (edit_[digit_] + 9) % 10; return "";
      default: break;
    }
    const int v = edit_[0] * 1000 + edit_[1] * 100 + edit_[2] * 10 + edit_[3];
    const bool speed = state_ == 5;
    state_ = speed ? 3 : 4;
    if (!speed) {
      angle_ = v;
      return "";
    }
    speed_ = fit(v, half_);
    return "speed";
  }
  if (key == Left) {
    state_ = state_ > 0 ? state_ - 1 : 0;
    return "";
  }
  if (key == Right) {
    state_ = state_ < 4 ? state_ + 1 : 4;
    return "";
  }
  switch (state_) {
    case 0:
      if (key == Set) return "start-stop";
      if (!running) mode_a_ = key == Plus;
      return "";
    case 1:
      if (key == Set || running) return "";
      half_ = key == Plus;
      speed_ = fit(speed_, half_);
      return "drive";
    case 2:
      if (key == Set) return "";
      right_ = key == Plus;
      return "direction";
    default:
      if (key != Set) return "";
      {
        const int v = state_ == 3 ? speed_ : angle_;
        edit_[0] = v / 1000;
        edit_[1] = v / 100 % 10;
        edit_[2] = v / 10 % 10;
        edit_[3] = v % 10;
      }
      digit_ = 0;
      state_ = state_ == 3 ? 5 : 6;
      return "";
  }
}

int MenuModel::indicator() const { return state_ >= 5 ? 6 : state_ + 1; }

int MenuModel::value(int angle_tenths) const {
  switch (state_) {
    case 0: return angle_tenths;
    case 4: return angle_;
    case 5:
    case 6: return edit_[0] * 1000 + edit_[1] * 100 + edit_[2] * 10 + edit_[3];
    default: return speed_;
  }
}

}  // namespace ap::model::hc08
