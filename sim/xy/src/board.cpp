// The simulated board's wiring (docs/sim.md "The simulated board"): the board core over the
// device models of sim/xy/rig/parts.hpp, through its Hardware callbacks; power-up, the 1 ms
// tick, and the checks run beside the core on every tick (the echo model, docs/sim.md "Echo
// checks"; the safety monitor; the delivery digest, "Delivery check"). The machine around the
// parts, the output files, the env() text and the QEMU target have files of their own
// (sim/xy/board.hpp lists them).
#include "sim/xy/board.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/xy/frame/command_codec.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/store.hpp"
#include "models/waveform/vcd.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "sim/xy/params.hpp"
#include "sim/xy/rig/rig_sensors.hpp"

namespace ap::sim::xy {
namespace {

namespace tmc = ap::xy_tmc2130;
namespace wf = ap::model::waveform;

// The inputs the echo model reads (models/xy/echo env_of), field by field.
bool same_env(const xy_board::Inputs& a, const xy_board::Inputs& b) {
  return a.endstop_min == b.endstop_min && a.endstop_max == b.endstop_max && a.usb == b.usb && a.charger == b.charger &&
         a.battery_mv == b.battery_mv && a.charge_ma == b.charge_ma && a.ble_status1 == b.ble_status1 &&
         a.ble_status2 == b.ble_status2;
}

}  // namespace

std::uint8_t led_code(const xy_board::Board& b) {
  // The core's Tab. 7-4 pattern (core/xy/board/led.hpp) in the telemetry's colour and blink bits.
  constexpr std::uint8_t kR = 1, kG = 2, kB = 4, kSlow = 1 << 4, kFast = 2 << 4;
  const xy_board::Led l = b.led();
  std::uint8_t code = 0;
  switch (l.colour) {
    case xy_board::LedColour::Off: return 0;
    case xy_board::LedColour::Red: code = kR; break;
    case xy_board::LedColour::Green: code = kG; break;
    case xy_board::LedColour::Blue: code = kB; break;
  }
  if (l.blink == xy_board::LedBlink::Slow) code |= kSlow;
  if (l.blink == xy_board::LedBlink::Fast) code |= kFast;
  return code;
}

SimBoard::SimBoard(BoardOptions opt) : opt_(std::move(opt)) {
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    endstop_min_um_[a] = machine_.endstop_min_um;
    endstop_max_um_[a] = machine_.endstop_max_um;
  }
  open_outputs();
}

SimBoard::~SimBoard() {
  try {
    finish();
  } catch (...) {
    // outputs are best effort in a destructor; finish() is normally called explicitly
  }
}

void SimBoard::seed_fram() {
  if (preboot_params_.empty()) return;
  xy_storage::ParameterStore store(parts_.fram.bus());
  (void)store.boot();
  xy_storage::ParameterSet set = store.current();
  for (const auto& [name, value] : preboot_params_) {
    const auto id = param_by_name(name);
    if (!id || !xy_storage::set_field(set, *id, value)) throw std::invalid_argument("bad parameter " + name);
  }
  if (!store.save(set).ok()) throw std::runtime_error("FRAM seeding failed");
  preboot_params_.clear();
}

void SimBoard::boot() {
  if (!board_) seed_fram();
  xy_board::Hardware hw;
  hw.ctx = this;
  // The buses reach the models through SimBoard, which records them on the waveforms and, on
  // the QEMU target, answers the mirror with the image's replies.
  hw.tmc = {tmc::SpiPort{&SimBoard::tmc_spi, this}, tmc::SpiPort{&SimBoard::tmc_spi_y, this}};
  hw.fram = xy_storage::SpiBus{&SimBoard::fram_spi, this};
  hw.i2c = xy_i2c::Port{&SimBoard::i2c_port, this};
  hw.sample = &SimBoard::sample;
  hw.motor = &SimBoard::motor;
  hw.uart_tx = &SimBoard::uart_tx;
  hw.led = &SimBoard::led_out;
  hw.encoder_zero = &SimBoard::encoder_zero;
  hw.power_off = &SimBoard::power_off;
  hw.charger_enable = &SimBoard::charger_enable;
  hw.frame_taken = &SimBoard::frame_taken;
  checker_.reset();   // it refers to the board it was made for
  board_ = std::make_unique<xy_board::Board>(hw);
  wave_boot_encoders();
  // What this boot will load (as `probe fram.NAME`), for the echo model's boot facts.
  const xy_storage::ParameterSet stored = model::xy_echo::stored_set(parts_.fram);
  if (!opt_.qemu_image.empty()) qemu_start();   // the image boots first; the mirror replays it
  (void)board_->boot();
  if (on_qemu()) qemu_after_tick(true);
  // A fresh echo model per power-up: boot facts from what the board sampled at boot (the
  // encoders, set by the carriage) and the stored parameters (docs/echo-model.md). Bytes still
  // in the old core's receive ring died with it, so the model's link twin starts empty too.
  model::xy_echo::Boot facts = model::xy_echo::boot_facts(*board_, board_->inputs(), stored);
  facts.sensors = sensors_now();
  checker_ = std::make_unique<model::xy_echo::BoardChecker>(*board_, facts);
  // The board's angle starts at 0 where the platform stands now; a turn in progress ends.
  turned_codes_ = 0;
  turn_to_codes_ = 0;
  parts_.gyro.chip.set_rate_mdps(0);
  ++boots_;
  monitor_ = model::xy_safety::BoardMonitor{};
  monitor_.booted(*board_);
}

void SimBoard::sample(void* ctx, xy_board::Inputs& in) {
  auto* s = static_cast<SimBoard*>(ctx);
  s->fill_inputs(in);
  s->sampled_ = in;
  ++s->samples_;
}

void SimBoard::motor(void* ctx, xy_board::Axis ax, const xy_board::MotorOutput& o) {
  auto* s = static_cast<SimBoard*>(ctx);
  const auto a = static_cast<std::size_t>(ax);
  // On the QEMU target the mirror's output must be the image's; where it is not, the image's
  // moves the carriage.
  s->motor_effect(a, s->on_qemu() ? s->mirror_motor(a, o) : o);
}

void SimBoard::encoder_zero(void* ctx, xy_board::Axis ax, std::int64_t counts) {
  auto* s = static_cast<SimBoard*>(ctx);
  const auto a = static_cast<std::size_t>(ax);
  if (s->on_qemu()) s->mirror_encoder_zero(a, counts);
  s->zero_encoder(a, counts);
}

void SimBoard::frame_taken(void* ctx, const xy_frame::CommandFrame& f) {
  // The exactly-once check of the PC (docs/sim.md "Delivery check"): every frame the core took,
  // across reboots, as the bytes the client formats for it.
  auto* s = static_cast<SimBoard*>(ctx);
  std::array<std::uint8_t, xy_codec::kCommandLength> bytes{};
  if (!xy_frame::format_command(f, bytes).ok()) {
    s->echo_disagreement("the core took a frame that does not format");
    return;
  }
  ++s->frames_taken_;
  s->taken_digest_ = fnv1a(s->taken_digest_, bytes);
}

void SimBoard::led_out(void* ctx, xy_board::LedColour lit) {
  // The LED is the core's (led()); only the image's pins need comparing.
  auto* s = static_cast<SimBoard*>(ctx);
  if (s->on_qemu()) s->mirror_led(lit);
}

void SimBoard::uart_tx(void* ctx, std::span<const std::uint8_t> bytes) {
  auto* s = static_cast<SimBoard*>(ctx);
  if (s->on_qemu()) {
    // The image's bytes go out; the mirror's must be the same ones.
    const std::span<const std::uint8_t> img = s->mirror_tx(bytes);
    if (!img.empty()) s->tx_effect(img);
    return;
  }
  s->tx_effect(bytes);
}

void SimBoard::tx_effect(std::span<const std::uint8_t> bytes) {
  tx_.insert(tx_.end(), bytes.begin(), bytes.end());
  echo_digests_.push_back(fnv1a(echo_digests_.empty() ? kFnvBasis : echo_digests_.back(), bytes));
  if (bytes.size() == xy_codec::kEchoLength) {
    model::xy_echo::EchoBytes e{};
    std::copy(bytes.begin(), bytes.end(), e.begin());
    tick_echoes_.push_back(e);
  } else {
    echo_disagreement("a TX write of " + std::to_string(bytes.size()) + " bytes, not one " +
                      std::to_string(xy_codec::kEchoLength) + "-byte echo");
  }
  if (wave_) {
    (void)wave_->uart(wf::BoardWaveforms::Uart::tx, static_cast<std::uint64_t>(ticks_) * kNsPerTick + 500'000U, bytes);
  }
}

void SimBoard::charger_enable(void* ctx, bool on) {
  auto* s = static_cast<SimBoard*>(ctx);
  // On the QEMU target the image drives the pin in the same tick; it must say the same.
  if (s->on_qemu()) s->mirror_charger(on);
  s->charging_enabled_ = on;
}

void SimBoard::power_off(void* ctx) {
  auto* s = static_cast<SimBoard*>(ctx);
  if (s->on_qemu()) s->mirror_kill();
  s->powered_off_ = true;
  s->button_at_off_ = true;
}

bool SimBoard::tmc_spi(void* ctx, const tmc::Datagram& tx, tmc::Datagram& rx) {
  return static_cast<SimBoard*>(ctx)->tmc_transfer(0, tx, rx);
}

bool SimBoard::tmc_spi_y(void* ctx, const tmc::Datagram& tx, tmc::Datagram& rx) {
  return static_cast<SimBoard*>(ctx)->tmc_transfer(1, tx, rx);
}

bool SimBoard::tmc_transfer(std::size_t a, const tmc::Datagram& tx, tmc::Datagram& rx) {
  if (on_qemu()) return replay(static_cast<std::uint8_t>(a), tx, rx);
  return tmc_device(a, tx, rx);
}

bool SimBoard::tmc_device(std::size_t a, const tmc::Datagram& tx, tmc::Datagram& rx) {
  rx = parts_.tmc[a].transfer(tx);
  if (wave_) {
    (void)wave_->spi(kDevTmcX + a, static_cast<std::uint64_t>(ticks_) * kNsPerTick + 100'000U, tx, rx);
  }
  return true;
}

bool SimBoard::fram_spi(void* ctx, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
  auto* s = static_cast<SimBoard*>(ctx);
  if (s->on_qemu()) {
    try {
      return s->replay(2, tx, rx);
    } catch (...) {
      return false;
    }
  }
  return s->fram_device(tx, rx);
}

bool SimBoard::fram_device(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
  const bool ok = parts_.fram.transfer(tx, rx);
  if (wave_) {
    try {
      (void)wave_->spi(kDevFram, static_cast<std::uint64_t>(ticks_) * kNsPerTick + 200'000U, tx,
                       std::span<const std::uint8_t>(rx.data(), rx.size()));
    } catch (...) {
      // a waveform failure must not change what the board sees
    }
  }
  return ok;
}

xy_i2c::Status SimBoard::i2c_port(void* ctx, std::uint8_t address, std::span<const std::uint8_t> tx,
                               std::span<std::uint8_t> rx) {
  return static_cast<SimBoard*>(ctx)->i2c_transfer(address, tx, rx);
}

xy_i2c::Status SimBoard::i2c_transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  // On QEMU the image's transactions drive the sensor models; the mirror's replay them.
  if (on_qemu()) return replay_i2c(address, tx, rx);
  return i2c_device(address, tx, rx);
}

xy_i2c::Status SimBoard::i2c_device(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  return parts_.i2c.transfer(address, tx, rx);
}

model::xy_echo::Sensors SimBoard::sensors_now() const { return sensors_of(parts_); }

void SimBoard::rx(std::span<const std::uint8_t> bytes) {
  if (!board_) boot();
  if (powered_off_) return;  // an unpowered UART takes nothing
  if (on_qemu()) {
    qemu_->link_write(bytes);
    link_delivered_ += static_cast<std::uint32_t>(bytes.size());
  }
  board_->uart_rx(bytes);
  checker_->rx(bytes);
  if (wave_) (void)wave_->uart(wf::BoardWaveforms::Uart::rx, static_cast<std::uint64_t>(now_us_) * 1000U, bytes);
}

std::vector<std::uint8_t> SimBoard::take_tx(std::size_t max_bytes) {
  const std::size_t n = std::min(tx_.size(), max_bytes / xy_codec::kEchoLength * xy_codec::kEchoLength);
  std::vector<std::uint8_t> out(tx_.begin(), tx_.begin() + static_cast<std::ptrdiff_t>(n));
  tx_.erase(tx_.begin(), tx_.begin() + static_cast<std::ptrdiff_t>(n));
  return out;
}

std::uint8_t SimBoard::led() const { return board_ && !powered_off_ ? led_code(*board_) : 0; }  // unpowered: dark

void SimBoard::advance_to(std::int64_t t_us) {
  if (!board_) boot();
  while ((static_cast<std::int64_t>(ticks_) + 1) * xy_axis::kTickUs <= t_us) tick();
}

void SimBoard::tick() {
  if (button_ && now_us_ >= button_until_us_) button_ = false;
  if (powered_off_) {
    // The KillSwitch cut the supply (docs/board.md "Button and shutdown"): nothing runs until
    // the button's controller switches the unit on again, which is a power-up.
    // A new press: the one that asked for the shutdown may still be held.
    const bool press = button_ && !button_at_off_;
    button_at_off_ = button_;
    if (press) {
      powered_off_ = false;
      parts_.power_cycle();
      boot();
    } else {
      for (std::size_t a = 0; a < xy_board::kAxes; ++a) motor_effect(a, xy_board::MotorOutput{false, 1, 0, 0});
      trace_tick();
      ++ticks_;
      now_us_ = static_cast<std::int64_t>(ticks_) * xy_axis::kTickUs;
      return;
    }
  }
  monitor_.before_tick(*board_);
  tick_echoes_.clear();
  const std::uint64_t samples = samples_;
  sensors_tick();
  if (on_qemu()) qemu_tick();
  parts_.drivers_tick();
  board_->tick();
  if (on_qemu()) qemu_after_tick(false);
  parts_.clear_logs();
  check_safety();
  // The checker gives the model the inputs the core kept (board.inputs()): they must be the
  // ones this tick's sample delivered, once per tick (docs/board.md "One cycle" step 1).
  if (samples_ != samples + 1) echo_disagreement("the core sampled its inputs " + std::to_string(samples_ - samples) + " times in a tick");
  if (!same_env(board_->inputs(), sampled_)) echo_disagreement("the core's inputs differ from what the hardware delivered");
  echoes_checked_ += tick_echoes_.size();
  for (const std::string& m : checker_->after_tick(tick_echoes_, sensors_now())) echo_disagreement(m);
  // The outcome oracle's ground truth (docs/sim.md "Outcome check"): what the model says
  // became of the frame taken in this tick, by its seq.
  if (const auto& f = checker_->model().fate_this_tick()) fates_[f->frame.seq] = *f;
  trace_tick();
  wave_expander();
  ++ticks_;
  now_us_ = static_cast<std::int64_t>(ticks_) * xy_axis::kTickUs;
  if (wave_ && ticks_ % 100 == 0) wave_->flush(ticks_ * static_cast<std::uint64_t>(kNsPerTick));
}

void SimBoard::echo_disagreement(const std::string& what) {
  ++echo_bad_count_;
  if (echo_bad_.size() < 20) {
    echo_bad_.push_back("at " + std::to_string(ticks_ + 1) + " ms (boot " + std::to_string(boots_) + "): " + what);
  }
}

void SimBoard::check_safety() {
  // The axis safety properties (models/xy/safety, the same monitor as the board fuzz target's),
  // after every tick.
  found_.clear();
  monitor_.after_tick(*board_, found_);
  for (const model::xy_safety::Violation& v : found_) {
    if (violations_.size() < 100) violations_.push_back({static_cast<std::int64_t>(v.tick) * 1000, v.axis, v.what});
  }
}

void SimBoard::finish() {
  if (finished_) return;
  finished_ = true;
  if (on_qemu()) qemu_stop();
  if (opt_.out_dir.empty()) return;
  if (!opt_.qemu_image.empty()) write_qemu_stats();
  write_outputs();
}

}  // namespace ap::sim::xy
