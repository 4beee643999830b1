// The board port (firmware/xy/board_port.hpp): what the core asks of the hardware, done with the
// peripheral layer. The encoders and the expander are read every tick with the other inputs;
// the expander's outputs (ENA) are written only when they change, since each change costs an
// SPI transaction (seed-000.md §4.14).
#include "firmware/xy/board_port.hpp"

#include <array>

#include "core/xy/axis/step_timer.hpp"
#include "firmware/xy/periph.hpp"

namespace ap::xy_fw {
namespace {

std::uint16_t tx_count = 0;
std::uint8_t olat_b = kOlatEnnX | kOlatEnnY;  // both drivers off until the core enables them
bool olat_written = false;

bool tmc(SpiDevice dev, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx) {
  return spi_transfer(dev, tx.data(), rx.data(), tx.size());
}
bool tmc_x(void*, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx) { return tmc(SpiDevice::TmcX, tx, rx); }
bool tmc_y(void*, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx) { return tmc(SpiDevice::TmcY, tx, rx); }

bool fram(void*, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
  if (tx.size() != rx.size()) return false;
  return spi_transfer(SpiDevice::Fram, tx.data(), rx.data(), tx.size());
}

xy_i2c::Status i2c_bus(void*, std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  return i2c_transfer(address, tx.data(), tx.size(), rx.data(), rx.size());
}

void sample(void*, xy_board::Inputs& in) {
  std::uint8_t mosi[4] = {kExpanderRead, kExpanderGpioA, 0, 0};
  std::uint8_t miso[4] = {};
  (void)spi_transfer(SpiDevice::Expander, mosi, miso, 4);
  const auto w = static_cast<std::uint16_t>(miso[2] | miso[3] << 8);
  in.endstop_min = {static_cast<std::uint8_t>((w & kExpXMin) != 0), static_cast<std::uint8_t>((w & kExpYMin) != 0)};
  in.endstop_max = {static_cast<std::uint8_t>((w & kExpXMax) != 0), static_cast<std::uint8_t>((w & kExpYMax) != 0)};
  in.charger = (w & kExpCharger) != 0;
  in.usb = (w & kExpUsb) != 0;
  in.ble_status1 = (w & kExpBle1) != 0;
  in.ble_status2 = (w & kExpBle2) != 0;
  in.button = (w & kExpButton) != 0;  // the button controller's off request (docs/board.md)
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    const std::uint8_t zero[4] = {};
    std::uint8_t e[4] = {};
    const bool ok = spi_transfer(a == 0 ? SpiDevice::EncoderX : SpiDevice::EncoderY, zero, e, 4);
    in.encoder[a] = ok ? encoder_reading(e) : xy_axis::EncoderReading{};
  }
  in.battery_mv = battery_mv(adc_read(AdcChannel::Battery));
  in.charge_ma = charge_ma(adc_read(AdcChannel::ChargeCurrent));
}

void expander_write(std::uint8_t reg, std::uint8_t value) {
  const std::uint8_t mosi[3] = {kExpanderWrite, reg, value};
  std::uint8_t miso[3] = {};
  (void)spi_transfer(SpiDevice::Expander, mosi, miso, 3);
}

void olat_write(std::uint8_t want) {
  if (want != olat_b || !olat_written) {
    olat_b = want;
    olat_written = true;
    expander_write(kExpanderOlatB, olat_b);
  }
}

void motor(void*, xy_board::Axis ax, const xy_board::MotorOutput& o) {
  const auto a = static_cast<std::size_t>(ax);
  const std::uint8_t enn = a == 0 ? kOlatEnnX : kOlatEnnY;
  olat_write(static_cast<std::uint8_t>(o.enable ? (olat_b & ~enn) : (olat_b | enn)));
  pin_write(a == 0 ? Pin::DirX : Pin::DirY, o.dir > 0);
  const auto t = xy_axis::step_timer(o.step_hz);
  if (o.enable && o.steps > 0 && t) {
    step_arm(a, t->psc, t->arr, o.steps);
  } else {
    step_arm(a, 0, 0, 0);
  }
}

void led(void*, xy_board::LedColour lit) {
  constexpr std::uint8_t kLed = kOlatLedR | kOlatLedG | kOlatLedB;
  std::uint8_t bit = 0;
  switch (lit) {
    case xy_board::LedColour::Off: break;
    case xy_board::LedColour::Red: bit = kOlatLedR; break;
    case xy_board::LedColour::Green: bit = kOlatLedG; break;
    case xy_board::LedColour::Blue: bit = kOlatLedB; break;
  }
  olat_write(static_cast<std::uint8_t>((olat_b & ~kLed) | bit));
}

void encoder_zero(void*, xy_board::Axis ax, std::int64_t counts) {
  const auto c = static_cast<std::uint32_t>(static_cast<std::int32_t>(counts));
  const std::uint8_t mosi[9] = {kOrbisUnlock[0], kOrbisUnlock[1], kOrbisUnlock[2], kOrbisUnlock[3], kOrbisSetPosition,
                                static_cast<std::uint8_t>(c >> 24), static_cast<std::uint8_t>(c >> 16),
                                static_cast<std::uint8_t>(c >> 8), static_cast<std::uint8_t>(c)};
  std::uint8_t miso[9] = {};
  (void)spi_transfer(ax == xy_board::Axis::X ? SpiDevice::EncoderX : SpiDevice::EncoderY, mosi, miso, sizeof mosi);
}

void power_off(void*) { pin_write(Pin::KillSwitch, true); }
void charger_enable(void*, bool on) { pin_write(Pin::ChargerEnable, on); }

void uart_tx(void*, std::span<const std::uint8_t> bytes) {
  link_send(bytes.data(), bytes.size());
  tx_count = static_cast<std::uint16_t>(tx_count + bytes.size());
}

}  // namespace

void port_init() {
  // The latch first, so the pins come up as "driver off, LED dark" when they become outputs.
  olat_write(olat_b);
  expander_write(kExpanderIodirB, kIodirB);
}

xy_board::Hardware board_hardware() {
  xy_board::Hardware hw;
  hw.tmc = {xy_tmc2130::SpiPort{&tmc_x, nullptr}, xy_tmc2130::SpiPort{&tmc_y, nullptr}};
  hw.fram = xy_storage::SpiBus{&fram, nullptr};
  hw.i2c = xy_i2c::Port{&i2c_bus, nullptr};  // TMP117 and ICM-20789 (docs/sensors.md)
  hw.sample = &sample;
  hw.motor = &motor;
  hw.uart_tx = &uart_tx;
  hw.led = &led;
  hw.encoder_zero = &encoder_zero;
  hw.power_off = &power_off;
  hw.charger_enable = &charger_enable;
  return hw;
}

std::uint16_t take_tx_count() {
  const std::uint16_t n = tx_count;
  tx_count = 0;
  return n;
}

}  // namespace ap::xy_fw
