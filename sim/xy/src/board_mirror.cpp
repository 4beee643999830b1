// The simulated board's host core as the QEMU image's mirror (docs/qemu.md "Co-simulation"):
// fed the same inputs, its SPI and I2C transfers are replayed from the image's (same device,
// same bytes, answered with the image's replies) and its outputs of a tick are held to the
// image's: motor outputs (the image's move the carriage), TX bytes (the image's go out), the
// LED, the encoder programming, the charger enable, the KillSwitch and the axes' positions.
// Each difference is a divergence, reported as a violation of the run. The image's own side
// (its session and the answers to its transactions) is board_qemu.cpp.
#include <algorithm>
#include <cstdio>

#include "core/xy/axis/step_timer.hpp"
#include "sim/xy/board.hpp"

namespace ap::sim::xy {

void SimBoard::qemu_fail(const std::string& what) {
  ++qemu_stats_.divergences;
  if (violations_.size() < 100) violations_.push_back({now_us_, -1, "QEMU: " + what});
}

bool SimBoard::replay(std::uint8_t dev, std::span<const std::uint8_t> mosi, std::span<std::uint8_t> miso) {
  if (qemu_log_pos_ >= qemu_log_.size()) {
    qemu_fail("the host core made an SPI transfer (device " + std::to_string(dev) + ") the image did not");
    std::fill(miso.begin(), miso.end(), std::uint8_t{0});
    return false;
  }
  const Transfer& t = qemu_log_[qemu_log_pos_++];
  if (t.dev != dev || !std::equal(t.mosi.begin(), t.mosi.end(), mosi.begin(), mosi.end()) || t.miso.size() != miso.size()) {
    qemu_fail("SPI transfer " + std::to_string(qemu_log_pos_) + " of the tick: the image sent " + std::to_string(t.mosi.size()) +
              " bytes to device " + std::to_string(t.dev) + ", the host core " + std::to_string(mosi.size()) + " to device " +
              std::to_string(dev) + (t.dev == dev && t.mosi.size() == mosi.size() ? " (different bytes)" : ""));
  }
  const std::size_t n = std::min(t.miso.size(), miso.size());
  std::copy_n(t.miso.begin(), n, miso.begin());
  return true;
}

xy_i2c::Status SimBoard::replay_i2c(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  const auto key = static_cast<std::uint8_t>(kI2cLogKey | address);
  if (qemu_log_pos_ >= qemu_log_.size()) {
    qemu_fail("the host core made an I2C transfer (address " + std::to_string(address) + ") the image did not");
    return xy_i2c::Status::BusError;
  }
  const Transfer& t = qemu_log_[qemu_log_pos_++];
  if (t.dev != key || !std::equal(t.mosi.begin(), t.mosi.end(), tx.begin(), tx.end()) || t.miso.size() != rx.size()) {
    qemu_fail("transfer " + std::to_string(qemu_log_pos_) + " of the tick: the image's (device " + std::to_string(t.dev) +
              ", " + std::to_string(t.mosi.size()) + " bytes out) is not the host core's I2C transfer to " +
              std::to_string(address));
  }
  std::copy_n(t.miso.begin(), std::min(t.miso.size(), rx.size()), rx.begin());
  return static_cast<xy_i2c::Status>(t.status);
}

void SimBoard::qemu_after_tick(bool boot) {
  if (!qemu_) return;
  if (qemu_log_pos_ != qemu_log_.size()) {
    qemu_fail("the image made " + std::to_string(qemu_log_.size() - qemu_log_pos_) + " SPI transfer(s) more than the host core");
  }
  if (image_tx_pos_ != image_tx_.size()) {
    qemu_fail("the image sent " + std::to_string(image_tx_.size() - image_tx_pos_) + " TX byte(s) more than the host core");
  }
  qemu_log_.clear();
  qemu_log_pos_ = 0;
  if (boot) return;
  const std::int32_t x = board_->axis_state(xy_board::Axis::X).pos;
  const std::int32_t y = board_->axis_state(xy_board::Axis::Y).pos;
  if (image_pos_[0] != x || image_pos_[1] != y) {
    qemu_fail("tick " + std::to_string(image_ticks_) + ": the image's axes are at (" + std::to_string(image_pos_[0]) + ", " +
              std::to_string(image_pos_[1]) + "), the host core's at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
  }
}

xy_board::MotorOutput SimBoard::mirror_motor(std::size_t a, const xy_board::MotorOutput& o) {
  // The same output (the timer's PSC and ARR those of the host core's rate) moves the carriage
  // as the host core's, its exact rate kept; a different one moves it as the image drives it.
  const ImageMotor& m = image_motor_[a];
  const bool enable = image_pin_low(a == 0 ? 0x40U : 0x80U);
  const auto t = xy_axis::step_timer(o.step_hz);
  const bool running = o.enable && o.steps > 0 && t.has_value();
  const bool same = enable == o.enable && m.dir == (o.dir > 0) && m.armed &&
                    (running ? (m.steps == o.steps && m.psc == t->psc && m.arr == t->arr) : m.steps == 0);
  if (same) return o;
  char buf[200];
  std::snprintf(buf, sizeof buf, "axis %c: image ENA %d DIR %d steps %d PSC %u ARR %u, host core ENA %d DIR %d steps %d at %u Hz",
                a == 0 ? 'X' : 'Y', enable ? 1 : 0, m.dir ? 1 : 0, m.steps, m.psc, m.arr, o.enable ? 1 : 0,
                o.dir > 0 ? 1 : 0, o.steps, o.step_hz);
  qemu_fail(buf);
  xy_board::MotorOutput img;
  img.enable = enable;
  img.dir = m.dir ? std::int8_t{1} : std::int8_t{-1};
  img.steps = m.steps;
  const std::uint64_t period = xy_axis::timer_period_clocks({m.psc, m.arr});
  img.step_hz = m.steps > 0 ? static_cast<std::uint32_t>(xy_axis::kTimerClockHz / period) : 0;
  return img;
}

std::span<const std::uint8_t> SimBoard::mirror_tx(std::span<const std::uint8_t> bytes) {
  const std::size_t have = image_tx_.size() - image_tx_pos_;
  const std::size_t n = std::min(have, bytes.size());
  const std::span<const std::uint8_t> img(image_tx_.data() + image_tx_pos_, n);
  image_tx_pos_ += n;
  if (n != bytes.size() || !std::equal(img.begin(), img.end(), bytes.begin())) {
    qemu_fail("TX: the image sent " + std::to_string(n) + " bytes where the host core sent " + std::to_string(bytes.size()) +
              (n == bytes.size() ? " different ones" : ""));
  }
  return img;
}

void SimBoard::mirror_led(xy_board::LedColour lit) {
  // The image drives the LED on OLATB bits 1..3 (R, G, B); it must light what the host core
  // lights in the same tick.
  const xy_board::LedColour image = image_pin_high(0x02U)   ? xy_board::LedColour::Red
                                    : image_pin_high(0x04U) ? xy_board::LedColour::Green
                                    : image_pin_high(0x08U) ? xy_board::LedColour::Blue
                                                            : xy_board::LedColour::Off;
  if (image != lit) {
    static constexpr const char* kName[] = {"off", "red", "green", "blue"};
    qemu_fail(std::string("LED: image ") + kName[static_cast<int>(image)] + ", host core " + kName[static_cast<int>(lit)]);
  }
}

void SimBoard::mirror_encoder_zero(std::size_t a, std::int64_t counts) {
  // The image programs the encoder over SPI in the same tick; it must ask for the same.
  const std::optional<std::int64_t> img = image_encoder_zero_[a];
  image_encoder_zero_[a].reset();
  if (!img || *img != counts) {
    qemu_fail(std::string("encoder ") + (a == 0 ? "X" : "Y") + ": image programmed " +
              (img ? std::to_string(*img) : std::string("nothing")) + ", host core " + std::to_string(counts));
  }
}

void SimBoard::mirror_charger(bool on) {
  if (image_charger_ != on) qemu_fail(std::string("charger enable: image ") + (image_charger_ ? "on" : "off"));
}

void SimBoard::mirror_kill() {
  if (!image_kill_) qemu_fail("KillSwitch: the host core pulled it, the image did not");
}

}  // namespace ap::sim::xy
