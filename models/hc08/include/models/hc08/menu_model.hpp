#pragma once
// The HC08 unit's menu and display as docs/hc08.md "Menu" states them, for the stateful test
// (properties/hc08/menu_test.cpp) and the key fuzz target: what the LCD must show and which
// settings must hold after every key. Its own tables; it shares no code with core/hc08_menu.
#include <cstdint>
#include <string>

namespace ap::model::hc08 {

class MenuModel {
 public:
  // key: 0 SET, 1 LEFT, 2 RIGHT, 3 PLUS, 4 MINUS. `running`: the motor turns (the drive and
  // the mode are changed only at rest). Returns what the unit must do: "start-stop",
  // "direction", "speed", "drive", or "".
  std::string press(int key, bool running);

  // The display (docs/hc08.md "Display") given the last angle the motor reported.
  int indicator() const;           // 1..6
  int value(int angle_tenths) const;  // digits 1-4
  bool error() const { return error_; }
  bool adjusted() const { return adjusted_; }  // the last key brought the speed into range

  // State and settings (the names of docs/hc08.md).
  std::string state() const { return kNames[state_]; }
  bool mode_a() const { return mode_a_; }
  bool half() const { return half_; }
  bool right() const { return right_; }
  int speed() const { return speed_; }
  int angle() const { return angle_; }

 private:
  static constexpr const char* kNames[7] = {"S_DEF", "SET_DRIVE", "SET_DIRECT", "SET_SPEED", "SET_ANGLE", "SET_SPEEDx", "SET_ANGLEx"};
  // The speed brought into the drive type's range; sets adjusted_ when it changed.
  int fit(int centi, bool half);

  int state_ = 0;
  int digit_ = 0;
  int edit_[4] = {0, 0, 0, 0};
  bool mode_a_ = true, half_ = false, right_ = true, error_ = false, adjusted_ = false;
  int speed_ = 100, angle_ = 90;
};

}  // namespace ap::model::hc08
