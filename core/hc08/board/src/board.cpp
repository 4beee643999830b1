// The HC08 unit's main loop and interrupts (board.hpp, docs/hc08.md "The board").
#include "core/hc08/board/board.hpp"

namespace ap::hc08_board {

namespace {
namespace m = hc08_menu;
}

Board::Board(hc08_drive::FullStep full, hc08_drive::PhaseOrder order) : motor_(full, order) { draw(); }

void Board::key_sample(std::uint8_t code) {
  if (const auto stable = debounce_.sample(code)) push_key(*stable);
}

void Board::push_key(std::uint8_t code) { queue_.push({Source::Keyboard, code}); }

bool Board::timer_match() {
  if (!motor_.on_match()) return false;
  queue_.push({Source::Motor, motor_.angle_tenths()});
  return true;
}

void Board::main_loop() {
  while (const auto msg = queue_.pop()) {
    if (msg->src == Source::Keyboard) {
      on_key(static_cast<std::uint8_t>(msg->data));
    } else {
      shown_angle_ = msg->data;
      if (menu_.state == m::State::Def) draw();  // the angle is shown in S_DEF only [T §5.2.2]
    }
  }
}

void Board::on_key(std::uint8_t code) {
  const auto key = decode(code);
  if (!key) {
    ++unknown_keys_;  // one of the seven unused keys: nothing happens [T: invalid keys do nothing]
    return;
  }
  const m::Action a = m::press(menu_, settings_, *key, motor_.running());
  display_.error = false;
  display_.adjusted = a == m::Action::SetSpeedAdjusted || a == m::Action::SetDriveAdjusted;
  switch (a) {
    case m::Action::StartStop:
      if (motor_.running()) {
        motor_.stop();
      } else {
        display_.error = motor_.start(settings_) != hc08_motor::Error::None;
      }
      break;
    case m::Action::SetDirection: motor_.set_direction(settings_.right); break;
    case m::Action::SetSpeed:
    case m::Action::SetSpeedAdjusted:
      if (motor_.running()) motor_.set_speed(settings_.speed_centi);  // fitted by the menu to this drive
      break;
    case m::Action::SetDrive:
    case m::Action::SetDriveAdjusted:
      // At rest (the menu allows it only then); the coils may move the rotor half a step, and
      // no step interrupt reports it, so the shown angle is taken here.
      motor_.set_drive(settings_.drive);
      shown_angle_ = motor_.angle_tenths();
      break;
    case m::Action::None:
    case m::Action::SetMode:
    case m::Action::SetAngle: break;
  }
  draw();  // the second pass (KB_NOCODE): the state is activated [T §5.2.5]
}

void Board::draw() {
  const bool editing = menu_.state == m::State::SpeedDigit || menu_.state == m::State::AngleDigit;
  display_.indicator = editing ? 6 : static_cast<std::uint8_t>(static_cast<std::uint8_t>(menu_.state) + 1U);
  display_.k2 = settings_.mode == hc08_motor::Mode::A;
  display_.k3 = !display_.k2;
  display_.direction = settings_.right ? 'r' : 'l';
  display_.drive = settings_.drive == hc08_drive::Drive::Full ? '4' : '8';
  switch (menu_.state) {
    case m::State::Def:
      display_.value = shown_angle_;
      display_.point = 1;
      break;
    case m::State::Angle:
      display_.value = settings_.angle_deg;
      display_.point = 0;
      break;
    case m::State::SpeedDigit:
    case m::State::AngleDigit:
      display_.value = m::value_of(menu_.edit);
      display_.point = menu_.state == m::State::SpeedDigit ? 2 : 0;
      break;
    case m::State::Drive:
    case m::State::Direction:
    case m::State::Speed:
      display_.value = settings_.speed_centi;  // [T: the other states show the speed]
      display_.point = 2;
      break;
  }
}

}  // namespace ap::hc08_board
