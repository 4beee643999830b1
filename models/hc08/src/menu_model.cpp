#include "models/hc08/menu_model.hpp"

namespace ap::model::hc08 {

// A speed the timer can make (docs/hc08.md "Timer"): 0.02 .. 20.00 rev/s full step, 0.01 ..
// 21.25 half step.
bool MenuModel::speed_ok(int centi, bool half) const {
  return half ? centi >= 1 && centi <= 2125 : centi >= 2 && centi <= 2000;
}

std::string MenuModel::press(int key, bool running) {
  enum { Set, Left, Right, Plus, Minus };
  error_ = false;
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
    if (!speed_ok(v, half_)) {
      error_ = true;
      return "";
    }
    speed_ = v;
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
      if (!speed_ok(speed_, key == Plus)) {
        error_ = true;
        return "";
      }
      half_ = key == Plus;
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
