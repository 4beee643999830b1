// The simulated board: the board core over virtual peripherals (docs/sim.md).
#include "sim/xy/board.hpp"
#include "sim/xy/outcome_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "models/xy/mechanics/mechanics.hpp"
#include "models/xy/safety/board_monitor.hpp"
#include "models/waveform/svg.hpp"
#include "models/waveform/vcd.hpp"
#include "protocol/xy/codec/layout.hpp"
#include "core/xy/axis/step_timer.hpp"
#include "core/xy/frame/command_codec.hpp"
#include "core/xy/storage/parameters.hpp"
#include "core/xy/storage/store.hpp"
#include "core/xy/tmc2130/fields.hpp"
#include "sim/xy/params.hpp"

namespace ap::sim::xy {
namespace {

namespace tmc = ap::xy_tmc2130;
namespace wf = ap::model::waveform;
namespace mech = ap::model::xy_mechanics;

constexpr std::int64_t kNsPerTick = 1'000'000;
constexpr std::size_t kDevTmcX = 0, kDevFram = 2, kDevEncX = 3, kDevExpander = 5;

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  std::string t;
  while (in >> t) w.push_back(t);
  return w;
}

std::int64_t to_int(const std::string& s) {
  std::size_t n = 0;
  const long long v = std::stoll(s, &n);
  if (n != s.size()) throw std::invalid_argument("not an integer: " + s);
  return v;
}

std::size_t axis_of(const std::string& s) {
  if (s == "x") return 0;
  if (s == "y") return 1;
  throw std::invalid_argument("axis must be x or y: " + s);
}

// The STEP edges of an axis as full steps (every `per_full` microsteps of net travel): the
// mechanics model fits the low-frequency kinematics, which a 16x thinner sequence keeps, and
// its cost grows with the number of steps inside its fit window.
std::vector<mech::Step> full_steps(const std::vector<std::int64_t>& edges_ns, const std::vector<std::int8_t>& dirs,
                                   std::int32_t per_full) {
  std::vector<mech::Step> out;
  out.reserve(edges_ns.size() / static_cast<std::size_t>(std::max(per_full, 1)) + 1);
  std::int64_t pos = 0;
  for (std::size_t i = 0; i < edges_ns.size(); ++i) {
    pos += dirs[i];
    if (pos % per_full == 0) out.push_back({static_cast<double>(edges_ns[i]) * 1e-9, dirs[i]});
  }
  return out;
}

}  // namespace

std::optional<xy_storage::ParamId> param_by_name(std::string_view name) {
  struct Alias {
    std::string_view name;
    xy_storage::ParamId id;
  };
  static constexpr Alias kAliases[] = {
      {"accel", xy_storage::ParamId::MaxAcceleration},  {"speed_fast", xy_storage::ParamId::FastSpeed},
      {"speed_slow", xy_storage::ParamId::SlowSpeed},     {"speed_start", xy_storage::ParamId::StartSpeed},
      {"lead", xy_storage::ParamId::LeadPitch},           {"steps", xy_storage::ParamId::StepsPerRev},
      {"irun", xy_storage::ParamId::RunCurrent},          {"ihold", xy_storage::ParamId::HoldCurrent},
  };
  for (const Alias& a : kAliases) {
    if (a.name == name) return a.id;
  }
  for (const xy_storage::MapEntry& e : xy_storage::kItemMap) {
    if (e.name == name && e.role != xy_storage::Role::Meta) return e.id;
  }
  return std::nullopt;
}

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

std::string led_word(std::uint8_t code) {
  static constexpr std::string_view kColours[] = {"off", "red", "green", "yellow", "blue", "magenta", "cyan", "white"};
  static constexpr std::string_view kBlink[] = {"", "_slow", "_fast", "_fast"};
  std::string w(kColours[code & 7U]);
  w.append(kBlink[(code >> 4) & 3U]);
  return w;
}

SimBoard::SimBoard(BoardOptions opt) : opt_(std::move(opt)) {
  i2c_.attach(tmp117_);
  i2c_.attach(gyro_);
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    endstop_min_um_[a] = machine_.endstop_min_um;
    endstop_max_um_[a] = machine_.endstop_max_um;
  }
  if (!opt_.out_dir.empty() && opt_.waveforms) {
    std::filesystem::create_directories(opt_.out_dir);
    vcd_file_ = std::make_unique<std::ofstream>(opt_.out_dir + "/waveforms.vcd", std::ios::trunc);
    wf::BoardWaveformConfig cfg;
    cfg.uart_baud = opt_.baud;
    wave_ = std::make_unique<wf::BoardWaveforms>(*vcd_file_, cfg);
  }
}

SimBoard::~SimBoard() {
  try {
    finish();
  } catch (...) {
    // outputs are best effort in a destructor; finish() is normally called explicitly
  }
}

std::int32_t SimBoard::usteps_per_rev(std::size_t a) const {
  // The chip's own MRES decides how far a STEP edge turns the motor, not the firmware's
  // parameter: a board whose MRES write never arrived moves 1/256 steps (docs/tmc2130.md
  // "Device model").
  return machine_.full_steps * tmc_[a].microsteps();
}

void SimBoard::seed_fram() {
  if (preboot_params_.empty()) return;
  xy_storage::ParameterStore store(fram_.bus());
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
  if (wave_) {
    // The encoders are read over SPI at power-up (eq. 7-2 seeds the step counters).
    for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
      xy_board::Inputs in;
      fill_inputs(in);
      const auto& e = in.encoder[a];
      const std::uint32_t word = (static_cast<std::uint32_t>(e.turns) & 0xFFFFU) << 16 | e.counts;
      const std::array<std::uint8_t, 4> miso{static_cast<std::uint8_t>(word >> 24), static_cast<std::uint8_t>(word >> 16),
                                             static_cast<std::uint8_t>(word >> 8), static_cast<std::uint8_t>(word)};
      const std::array<std::uint8_t, 4> mosi{};
      (void)wave_->spi(kDevEncX + a, static_cast<std::uint64_t>(now_us_) * 1000U, mosi, miso);
    }
  }
  // What this boot will load (as `probe fram.NAME`), for the echo model's boot facts.
  const xy_storage::ParameterSet stored = model::xy_echo::stored_set(fram_);
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
  gyro_.set_rate_mdps(0);
  ++boots_;
  monitor_ = model::xy_safety::BoardMonitor{};
  monitor_.booted(*board_);
}

std::int64_t SimBoard::encoder_raw_counts(std::size_t a) const {
  const double revs = carriage_um_[a] / machine_.lead_um;
  return static_cast<std::int64_t>(std::floor(revs * xy_axis::kEncoderCounts + 1e-9));
}

void SimBoard::encoder_zero(void* ctx, xy_board::Axis ax, std::int64_t counts) {
  auto* s = static_cast<SimBoard*>(ctx);
  const auto a = static_cast<std::size_t>(ax);
  if (s->on_qemu()) {
    // The image programs the encoder over SPI in the same tick; it must ask for the same.
    const std::optional<std::int64_t> img = s->image_encoder_zero_[a];
    s->image_encoder_zero_[a].reset();
    if (!img || *img != counts) {
      s->qemu_fail(std::string("encoder ") + (a == 0 ? "X" : "Y") + ": image programmed " +
                   (img ? std::to_string(*img) : std::string("nothing")) + ", host core " + std::to_string(counts));
    }
  }
  s->encoder_offset_[a] = s->encoder_raw_counts(a) - counts;
}

void SimBoard::fill_inputs(xy_board::Inputs& in) {
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    const double c = carriage_um_[a];
    auto level = [](std::int8_t force, bool physical) -> std::uint8_t {
      if (force > 0) return 1;
      if (force < 0) return 0;
      return physical ? 1 : 0;
    };
    in.endstop_min[a] = level(endstop_force_[a][0], c <= endstop_min_um_[a]);
    in.endstop_max[a] = level(endstop_force_[a][1], c >= endstop_max_um_[a]);
    // RLS Orbis: multi-turn count and a 14-bit angle of the screw (one turn = one lead),
    // measured from its programmed zero.
    const std::int64_t total = encoder_raw_counts(a) - encoder_offset_[a];
    const std::int64_t turns = total >= 0 ? total / xy_axis::kEncoderCounts : -((-total + xy_axis::kEncoderCounts - 1) / xy_axis::kEncoderCounts);
    const std::int64_t counts = total - turns * xy_axis::kEncoderCounts;
    // An encoder taken off the board ("encoder off"): it answers nothing valid.
    in.encoder[a] = xy_axis::EncoderReading{static_cast<std::int32_t>(turns), static_cast<std::uint16_t>(counts),
                                         encoder_fitted_ ? std::uint8_t{1} : std::uint8_t{0}};
  }
  in.usb = usb_;
  in.charger = charger_;
  in.button = button_;
  in.battery_mv = battery_mv_;
  // Power module: charging current positive, discharge negative (more while a motor runs).
  const bool running = out_[0].steps != 0 || out_[1].steps != 0;
  // The board's charger enable (Hardware::charger_enable) gates the charging current.
  in.charge_ma = (charger_ || usb_) && charging_enabled_ ? 500 : (running ? -650 : -120);
  switch (ble_) {   // Tab. 7-2: (STATUS1_IND, STATUS2_IND)
    case Ble::Shutdown: in.ble_status1 = true; in.ble_status2 = true; break;
    case Ble::Standby: in.ble_status1 = true; in.ble_status2 = false; break;
    case Ble::Connected: in.ble_status1 = false; in.ble_status2 = false; break;
    case Ble::Session: in.ble_status1 = false; in.ble_status2 = true; break;
  }
}

std::uint16_t SimBoard::expander_word() const { return board_ ? expander_word(board_->inputs()) : 0; }

void SimBoard::sample(void* ctx, xy_board::Inputs& in) {
  auto* s = static_cast<SimBoard*>(ctx);
  s->fill_inputs(in);
  s->sampled_ = in;
  ++s->samples_;
}

namespace {
// The inputs the echo model reads (models/xy/echo env_of), field by field.
bool same_env(const xy_board::Inputs& a, const xy_board::Inputs& b) {
  return a.endstop_min == b.endstop_min && a.endstop_max == b.endstop_max && a.usb == b.usb && a.charger == b.charger &&
         a.battery_mv == b.battery_mv && a.charge_ma == b.charge_ma && a.ble_status1 == b.ble_status1 &&
         a.ble_status2 == b.ble_status2;
}
}  // namespace

void SimBoard::motor(void* ctx, xy_board::Axis ax, const xy_board::MotorOutput& o) {
  auto* s = static_cast<SimBoard*>(ctx);
  const auto a = static_cast<std::size_t>(ax);
  if (s->on_qemu()) {
    // The image's outputs move the carriage; the mirror's must be the same.
    const ImageMotor& m = s->image_motor_[a];
    const bool enable = s->image_pin_low(a == 0 ? 0x40U : 0x80U);
    const auto t = xy_axis::step_timer(o.step_hz);
    const bool running = o.enable && o.steps > 0 && t.has_value();
    const bool same = enable == o.enable && m.dir == (o.dir > 0) && m.armed &&
                      (running ? (m.steps == o.steps && m.psc == t->psc && m.arr == t->arr) : m.steps == 0);
    if (!same) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "axis %c: image ENA %d DIR %d steps %d PSC %u ARR %u, host core ENA %d DIR %d steps %d at %u Hz",
                    a == 0 ? 'X' : 'Y', enable ? 1 : 0, m.dir ? 1 : 0, m.steps, m.psc, m.arr, o.enable ? 1 : 0,
                    o.dir > 0 ? 1 : 0, o.steps, o.step_hz);
      s->qemu_fail(buf);
      xy_board::MotorOutput img;
      img.enable = enable;
      img.dir = m.dir ? std::int8_t{1} : std::int8_t{-1};
      img.steps = m.steps;
      const std::uint64_t period = xy_axis::timer_period_clocks({m.psc, m.arr});
      img.step_hz = m.steps > 0 ? static_cast<std::uint32_t>(xy_axis::kTimerClockHz / period) : 0;
      s->motor_effect(a, img);
      return;
    }
  }
  s->motor_effect(a, o);
}

void SimBoard::motor_effect(std::size_t a, const xy_board::MotorOutput& o) {
  SimBoard* s = this;
  s->out_[a] = o;
  const std::int64_t t0 = static_cast<std::int64_t>(s->ticks_) * kNsPerTick;
  xy_axis::Output out;
  out.steps = o.steps;   // the STEP pin toggles whatever the driver does with it
  out.dir = o.dir;
  out.step_speed = static_cast<std::int32_t>(std::min<std::uint64_t>(std::uint64_t{o.step_hz} * xy_axis::kSpeedScale,
                                                                     xy_axis::kFineSpeedMax));
  std::vector<std::int64_t> edges;
  s->clock_[a].tick(t0, out, edges);
  // The driver decides whether the edges turn the motor (DRV_ENN, CHOPCONF.TOFF) and how far
  // (CHOPCONF.MRES): the TMC2130 model, in 1/256 full steps.
  tmc_[a].set_drv_enn(!o.enable);
  const std::int64_t turned = tmc_[a].step(static_cast<std::int64_t>(edges.size()), o.dir);
  const double um_per_256th = static_cast<double>(s->machine_.lead_um) / (256.0 * s->machine_.full_steps);
  s->carriage_um_[a] += um_per_256th * static_cast<double>(turned);
  AxisRec& r = s->rec_[a];
  if (turned != 0) {
    for (const std::int64_t e : edges) {
      r.edges_ns.push_back(e);
      r.dirs.push_back(o.dir);
    }
  }
  if (s->wave_) {
    const bool dir = o.dir > 0;
    if (dir != s->wave_dir_[a] || s->ticks_ == 0) s->wave_->dir(a, static_cast<std::uint64_t>(t0), dir);
    if (o.enable != s->wave_ena_[a] || s->ticks_ == 0) s->wave_->ena(a, static_cast<std::uint64_t>(t0), o.enable);
    s->wave_dir_[a] = dir;
    s->wave_ena_[a] = o.enable;
    for (const std::int64_t e : edges) s->wave_->step(a, static_cast<std::uint64_t>(e));
  }
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
  auto* s = static_cast<SimBoard*>(ctx);
  if (!s->on_qemu()) return;
  // The image drives the LED on OLATB bits 1..3 (R, G, B); it must light what the host core
  // lights in the same tick.
  const xy_board::LedColour image = s->image_pin_high(0x02U)   ? xy_board::LedColour::Red
                                 : s->image_pin_high(0x04U) ? xy_board::LedColour::Green
                                 : s->image_pin_high(0x08U) ? xy_board::LedColour::Blue
                                                            : xy_board::LedColour::Off;
  if (image != lit) {
    static constexpr const char* kName[] = {"off", "red", "green", "blue"};
    s->qemu_fail(std::string("LED: image ") + kName[static_cast<int>(image)] + ", host core " + kName[static_cast<int>(lit)]);
  }
}

void SimBoard::uart_tx(void* ctx, std::span<const std::uint8_t> bytes) {
  auto* s = static_cast<SimBoard*>(ctx);
  if (s->on_qemu()) {
    // The image's bytes go out; the mirror's must be the same ones.
    const std::size_t have = s->image_tx_.size() - s->image_tx_pos_;
    const std::size_t n = std::min(have, bytes.size());
    const std::span<const std::uint8_t> img(s->image_tx_.data() + s->image_tx_pos_, n);
    s->image_tx_pos_ += n;
    if (n != bytes.size() || !std::equal(img.begin(), img.end(), bytes.begin())) {
      s->qemu_fail("TX: the image sent " + std::to_string(n) + " bytes where the host core sent " +
                   std::to_string(bytes.size()) + (n == bytes.size() ? " different ones" : ""));
    }
    if (n > 0) s->tx_effect(img);
    return;
  }
  s->tx_effect(bytes);
}

void SimBoard::tx_effect(std::span<const std::uint8_t> bytes) {
  SimBoard* s = this;
  s->tx_.insert(s->tx_.end(), bytes.begin(), bytes.end());
  s->echo_digests_.push_back(fnv1a(s->echo_digests_.empty() ? kFnvBasis : s->echo_digests_.back(), bytes));
  if (bytes.size() == xy_codec::kEchoLength) {
    model::xy_echo::EchoBytes e{};
    std::copy(bytes.begin(), bytes.end(), e.begin());
    s->tick_echoes_.push_back(e);
  } else {
    s->echo_disagreement("a TX write of " + std::to_string(bytes.size()) + " bytes, not one " +
                         std::to_string(xy_codec::kEchoLength) + "-byte echo");
  }
  if (s->wave_) {
    (void)s->wave_->uart(wf::BoardWaveforms::Uart::tx, static_cast<std::uint64_t>(s->ticks_) * kNsPerTick + 500'000U,
                         bytes);
  }
}

bool SimBoard::tmc_transfer(std::size_t a, const tmc::Datagram& tx, tmc::Datagram& rx) {
  if (on_qemu()) return replay(static_cast<std::uint8_t>(a), tx, rx);
  return tmc_device(a, tx, rx);
}

bool SimBoard::tmc_device(std::size_t a, const tmc::Datagram& tx, tmc::Datagram& rx) {
  rx = tmc_[a].transfer(tx);
  if (wave_) {
    (void)wave_->spi(kDevTmcX + a, static_cast<std::uint64_t>(ticks_) * kNsPerTick + 100'000U, tx, rx);
  }
  return true;
}

xy_i2c::Status SimBoard::i2c_transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  // On QEMU the image's transactions drive the sensor models; the mirror's replay them.
  if (on_qemu()) return replay_i2c(address, tx, rx);
  return i2c_device(address, tx, rx);
}

xy_i2c::Status SimBoard::i2c_device(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  const xy_i2c::Status s = i2c_.transfer(address, tx, rx);
  i2c_.clear_log();   // the bus's log is a test hook; a run would only grow it
  return s;
}

xy_i2c::Status SimBoard::i2c_port(void* ctx, std::uint8_t address, std::span<const std::uint8_t> tx,
                               std::span<std::uint8_t> rx) {
  return static_cast<SimBoard*>(ctx)->i2c_transfer(address, tx, rx);
}

namespace {
// docs/sim.md "rotate": the platform turns at 90 °/s, code 11790 at ±250 °/s (131 LSB per
// °/s, DS-000169 Table 1): 90 m° per 1 ms tick. Every code sent is a multiple of 131, so each
// tick turns the board's integrated angle by whole m° and the last one lands exactly.
constexpr std::int64_t kGyroLsbPerDps = 131;
constexpr std::int64_t kTurnMdegPerTick = 90;
}  // namespace

void SimBoard::sensors_tick() {
  tmp117_.advance_ms(1);
  const std::int64_t left = turn_to_codes_ - turned_codes_;
  const std::int64_t step = std::clamp(left, -kTurnMdegPerTick * kGyroLsbPerDps, kTurnMdegPerTick * kGyroLsbPerDps);
  // In m°/s: step / 131 m° per 1 ms tick; the model's nearest code is then exactly `step`.
  gyro_.set_rate_mdps(static_cast<std::int32_t>(step / kGyroLsbPerDps * 1000));
  turned_codes_ += step;
}

model::xy_echo::Sensors SimBoard::sensors_now() const {
  return model::xy_echo::sensors_of(tmp117_, xy_i2c::Status::Ok, gyro_, xy_i2c::Status::Ok);
}

bool SimBoard::tmc_spi(void* ctx, const tmc::Datagram& tx, tmc::Datagram& rx) {
  return static_cast<SimBoard*>(ctx)->tmc_transfer(0, tx, rx);
}

bool SimBoard::tmc_spi_y(void* ctx, const tmc::Datagram& tx, tmc::Datagram& rx) {
  return static_cast<SimBoard*>(ctx)->tmc_transfer(1, tx, rx);
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
  SimBoard* s = this;
  const bool ok = s->fram_.transfer(tx, rx);
  if (s->wave_) {
    try {
      (void)s->wave_->spi(kDevFram, static_cast<std::uint64_t>(s->ticks_) * kNsPerTick + 200'000U, tx,
                          std::span<const std::uint8_t>(rx.data(), rx.size()));
    } catch (...) {
      // a waveform failure must not change what the board sees
    }
  }
  return ok;
}

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
      power_cycle_parts();
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
  for (auto& d : tmc_) d.elapse_us(xy_axis::kTickUs);
  board_->tick();
  if (on_qemu()) qemu_after_tick(false);
  for (auto& d : tmc_) d.clear_log();
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
  const std::uint16_t w = expander_word();
  if (w != expander_last_ && wave_) {
    // MCP23S17-style read of GPIOA/B after the interrupt line fired.
    const std::array<std::uint8_t, 4> mosi{0x41, 0x12, 0, 0};
    const std::array<std::uint8_t, 4> miso{0, 0, static_cast<std::uint8_t>(w & 0xFFU), static_cast<std::uint8_t>(w >> 8)};
    (void)wave_->spi(kDevExpander, static_cast<std::uint64_t>(ticks_) * kNsPerTick + 300'000U, mosi, miso);
  }
  expander_last_ = w;
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

void SimBoard::trace_tick() {
  const xy_board::Board& b = *board_;
  const std::int64_t t_us = static_cast<std::int64_t>(ticks_) * 1000;
  const std::uint8_t led_now = led();
  const double um_per_ustep =
      static_cast<double>(b.mechanics().pitch_um) / (static_cast<double>(b.mechanics().steps_per_rev) * b.mechanics().microsteps);
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    const auto ax = static_cast<xy_board::Axis>(a);
    const xy_axis::State& s = b.axis_state(ax);
    const xy_board::MotorOutput& o = b.motor_output(ax);
    const xy_board::Inputs& in = b.inputs();
    if (!opt_.out_dir.empty()) {
      char buf[512];
      std::snprintf(buf, sizeof buf,
                    "%lld,%c,%s,%s,%d,%d,%d,%d,%u,%u,%d,%d,%c,%d,%d,%d,%d,%u,%d,%d,%s,%.3f,%d,%u,%d,%d,%lld,0x%03x",
                    static_cast<long long>(t_us), a == 0 ? 'X' : 'Y', xy_axis::phase_name(s.phase), xy_axis::mode_name(s.mode),
                    s.pos, s.target, s.v / xy_axis::kSpeedScale, o.dir, in.endstop_min[a], in.endstop_max[a],
                    b.block() != xy_board::Block::None ? 1 : 0, o.enable ? o.steps : 0,
                    xy_axis::edge_letter(b.axis_edge(ax)), static_cast<int>(b.axis_error(ax)),
                    static_cast<int>(b.main_state()), static_cast<int>(b.block()), b.session_open() ? 1 : 0,
                    in.battery_mv, in.charger ? 1 : 0, in.usb ? 1 : 0, led_word(led_now).c_str(), carriage_um_[a],
                    in.encoder[a].turns, in.encoder[a].counts, o.enable ? 1 : 0, b.link_alive() ? 1 : 0,
                    static_cast<long long>(b.counters().dispatched_frames), expander_word());
      trace_rows_.emplace_back(buf);
    }
    if (!opt_.out_dir.empty() && (ticks_ % 5 == 0)) {
      plot_t_[a].push_back(static_cast<double>(t_us) / 1e6);
      plot_pos_[a].push_back(s.pos * um_per_ustep / 1000.0);
      plot_v_[a].push_back(s.v / static_cast<double>(xy_axis::kSpeedScale) * um_per_ustep / 1000.0 * s.dir);
    }
  }
  path_tick(um_per_ustep);
}

void SimBoard::path_tick(double um_per_ustep) {
  const xy_path::Executor& p = board_->path();
  const bool active = p.active();
  if (opt_.out_dir.empty() || (!active && !path_was_active_)) {
    path_was_active_ = active;
    return;
  }
  path_was_active_ = active;
  const xy_scurve::Kinematics k = p.kinematics();
  const double mm = um_per_ustep / 1000.0;  // one move is one step of the driving axis
  PathRow r;
  r.t_s = static_cast<double>(ticks_) / 1000.0;
  r.x_mm = board_->axis_state(xy_board::Axis::X).pos * mm;
  r.y_mm = board_->axis_state(xy_board::Axis::Y).pos * mm;
  r.carriage_x_mm = carriage_um_[0] / 1000.0;
  r.carriage_y_mm = carriage_um_[1] / 1000.0;
  r.v = static_cast<double>(k.vel_milli) / 1000.0 * mm;
  r.a = static_cast<double>(k.accel_milli) / 1000.0 * mm;
  r.j = static_cast<double>(k.jerk_milli) / 1000.0 * mm;
  path_rows_.push_back(r);
}

void SimBoard::write_path_outputs() const {
  if (path_rows_.empty()) return;
  {
    std::ofstream c(opt_.out_dir + "/path.csv", std::ios::trunc);
    c << "t_s,x_mm,y_mm,carriage_x_mm,carriage_y_mm,v_mm_s,a_mm_s2,j_mm_s3\n";
    char buf[256];
    for (const PathRow& r : path_rows_) {
      std::snprintf(buf, sizeof buf, "%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", r.t_s, r.x_mm, r.y_mm, r.carriage_x_mm,
                    r.carriage_y_mm, r.v, r.a, r.j);
      c << buf;
    }
  }
  std::array<wf::Panel, 3> panels;
  const std::array<std::pair<const char*, const char*>, 3> names{
      {{"Speed along the driving axis", "v [mm/s]"}, {"Acceleration", "a [mm/s^2]"}, {"Jerk", "j [mm/s^3]"}}};
  for (std::size_t i = 0; i < panels.size(); ++i) {
    panels[i].title = names[i].first;
    panels[i].x_label = "t [s]";
    panels[i].y_label = names[i].second;
    wf::Series s;
    s.label = names[i].second;
    for (const PathRow& r : path_rows_) {
      s.x.push_back(r.t_s);
      s.y.push_back(i == 0 ? r.v : (i == 1 ? r.a : r.j));
    }
    panels[i].series.push_back(std::move(s));
  }
  std::ofstream o(opt_.out_dir + "/profile.svg", std::ios::trunc);
  wf::write_svg(o, "Board " + std::to_string(opt_.id) + ": the path's S-curve (seed-003.md Fig. 30)", panels);
}

void SimBoard::power_cycle_parts() {
  // Power cycle: the drivers and the sensors lose their registers, the FRAM (and the
  // encoder's programmed zero) keep their contents.
  for (auto& d : tmc_) d.power_cycle();
  tmp117_.power_on_reset();
  gyro_.power_on_reset();
}

void SimBoard::charger_enable(void* ctx, bool on) {
  auto* s = static_cast<SimBoard*>(ctx);
  // On the QEMU target the image drives the pin in the same tick; it must say the same.
  if (s->on_qemu() && s->image_charger_ != on) s->qemu_fail(std::string("charger enable: image ") + (s->image_charger_ ? "on" : "off"));
  s->charging_enabled_ = on;
}

void SimBoard::power_off(void* ctx) {
  auto* s = static_cast<SimBoard*>(ctx);
  if (s->on_qemu() && !s->image_kill_) s->qemu_fail("KillSwitch: the host core pulled it, the image did not");
  s->powered_off_ = true;
  s->button_at_off_ = true;
}

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

mech::Result SimBoard::mechanics(std::size_t a) const {
  const AxisRec& r = rec_[a];
  mech::Params p;
  p.axis.lead = machine_.lead_um * 1e-6;
  p.axis.microsteps = 1;   // full steps (full_steps() above)
  const std::int32_t per_full = std::max(1, usteps_per_rev(a) / machine_.full_steps);
  const std::vector<mech::Step> steps = full_steps(r.edges_ns, r.dirs, per_full);
  if (steps.empty()) return {};
  return mech::simulate(mech::Model(p), steps);
}

std::size_t SimBoard::lost_step_risks(std::size_t a) {
  if (!risk_cache_[a] || risk_cache_edges_[a] != rec_[a].edges_ns.size()) {
    risk_cache_[a] = mechanics(a).summary.lost_step_risks;
    risk_cache_edges_[a] = rec_[a].edges_ns.size();
  }
  return *risk_cache_[a];
}

std::string SimBoard::probe(const std::string& subject) {
  if (subject.rfind("tmc.", 0) == 0 && subject.size() > 6) {
    const std::size_t a = axis_of(subject.substr(4, 1));
    const std::string field = subject.substr(6);
    for (const tmc::FieldInfo& f : tmc::kFields) {
      if (f.name == field) return std::to_string(tmc::field_get(tmc_[a].chip_register(f.reg), f.field));
    }
    throw std::invalid_argument("unknown TMC2130 field " + field);
  }
  if (subject.rfind("fram.", 0) == 0) {
    const auto id = param_by_name(subject.substr(5));
    if (!id) throw std::invalid_argument("unknown parameter " + subject.substr(5));
    // What a fresh boot would load: a copy of the chip, read by a store of its own.
    return std::to_string(*xy_storage::get_field(model::xy_echo::stored_set(fram_), *id));
  }
  if (subject == "x.lost_steps" || subject == "y.lost_steps") return std::to_string(lost_step_risks(axis_of(subject.substr(0, 1))));
  if (subject == "lost_steps") return std::to_string(lost_step_risks(0) + lost_step_risks(1));
  if (subject == "watchdog_stops") return std::to_string(board_->counters().watchdog_expiries);
  if (subject.rfind("fate.", 0) == 0) {
    // fate.SEQ: the last frame taken with that seq, as sim/xy/outcome_oracle.hpp writes it.
    const auto it = fates_.find(static_cast<std::uint16_t>(to_int(subject.substr(5))));
    return it == fates_.end() ? std::string("none") : fate_text(it->second);
  }
  if (subject == "taken") return std::to_string(frames_taken_) + " " + std::to_string(taken_digest_);
  if (subject == "gated") return std::to_string(board_->counters().gated_frames);
  if (subject == "violations") {
    std::string s = std::to_string(violations_.size());
    if (!violations_.empty()) {
      const Violation& v = violations_.front();
      s += " first at " + std::to_string(v.t_us) + " us, axis " + std::to_string(v.axis) + ": " + v.what;
    }
    return s;
  }
  if (subject == "echo_model") {
    // "CHECKED BAD": echoes compared with the model, disagreements.
    return std::to_string(echoes_checked_) + " " + std::to_string(echo_bad_count_);
  }
  if (subject.rfind("echo_model.", 0) == 0) {
    // echo_model.K.OFF: 100 characters of the K-th kept disagreement from OFF (a bus reply
    // carries at most dds::kFrameMax bytes), empty past its end.
    const std::string rest = subject.substr(11);
    const std::size_t dot = rest.find('.');
    if (dot == std::string::npos) throw std::invalid_argument("probe echo_model.K.OFF");
    const auto k = static_cast<std::size_t>(to_int(rest.substr(0, dot)));
    const auto off = static_cast<std::size_t>(to_int(rest.substr(dot + 1)));
    if (k >= echo_bad_.size()) throw std::invalid_argument("no disagreement " + rest.substr(0, dot));
    return off < echo_bad_[k].size() ? echo_bad_[k].substr(off, 100) : std::string();
  }
  if (subject.rfind("echo_sent.", 0) == 0) {
    // echo_sent.N: "TOTAL DIGEST_N QUEUED": echoes the core sent, the digest of the TX stream
    // after the first N of them, and the echoes still waiting in the TX queue.
    const auto n = static_cast<std::size_t>(to_int(subject.substr(10)));
    if (n > echo_digests_.size()) throw std::invalid_argument("only " + std::to_string(echo_digests_.size()) + " echoes sent");
    return std::to_string(echo_digests_.size()) + " " + std::to_string(n == 0 ? kFnvBasis : echo_digests_[n - 1]) + " " +
           std::to_string(tx_.size() / xy_codec::kEchoLength);
  }
  if (subject == "carriage.x" || subject == "carriage.y") {
    return std::to_string(static_cast<long long>(std::llround(carriage_um_[axis_of(subject.substr(9))])));
  }
  throw std::invalid_argument("unknown probe " + subject);
}

std::string SimBoard::env(const std::string& line) {
  try {
    const std::vector<std::string> w = words(line);
    if (w.empty()) return "err empty";
    const std::string& k = w[0];
    auto need = [&](std::size_t n) {
      if (w.size() != n) throw std::invalid_argument("'" + k + "' takes " + std::to_string(n - 1) + " arguments");
    };
    auto preboot = [&] {
      if (board_) throw std::invalid_argument("'" + k + "' is a setup command (before boot)");
    };
    if (k == "probe") {
      need(2);
      if (!board_) boot();
      return "ok " + probe(w[1]);
    }
    if (k == "pos") {
      need(3);
      preboot();
      carriage_um_[axis_of(w[1])] = static_cast<double>(to_int(w[2]));
    } else if (k == "endstop_at") {
      need(4);
      const std::size_t a = axis_of(w[1]);
      (w[2] == "min" ? endstop_min_um_ : endstop_max_um_)[a] = static_cast<std::int32_t>(to_int(w[3]));
    } else if (k == "param" || k == "fram") {
      need(3);
      preboot();
      if (!param_by_name(w[1])) throw std::invalid_argument("unknown parameter " + w[1]);
      preboot_params_.emplace_back(w[1], to_int(w[2]));
    } else if (k == "boot") {
      need(1);
      if (!board_) boot();
    } else if (k == "battery") {
      need(2);
      battery_mv_ = static_cast<std::uint16_t>(std::clamp<std::int64_t>(to_int(w[1]), 0, 65535));
    } else if (k == "charger" || k == "usb") {
      need(2);
      (k == "charger" ? charger_ : usb_) = to_int(w[1]) != 0;
    } else if (k == "temperature") {
      need(2);
      tmp117_.set_temperature_mc(static_cast<std::int32_t>(std::clamp<std::int64_t>(to_int(w[1]), -300'000, 300'000)));
    } else if (k == "rotate") {
      need(2);
      // The shorter way from where the turn stands now (the board's frame: 0 at its power-up)
      // to the angle asked for; a half turn goes forward.
      const std::int64_t want = ((to_int(w[1]) % 360'000) + 360'000) % 360'000;
      const std::int64_t now = ((turned_codes_ / kGyroLsbPerDps) % 360'000 + 360'000) % 360'000;
      std::int64_t delta = (want - now + 360'000) % 360'000;
      if (delta > 180'000) delta -= 360'000;
      turn_to_codes_ = turned_codes_ + delta * kGyroLsbPerDps;
    } else if (k == "ble") {
      need(2);
      if (w[1] == "shutdown") ble_ = Ble::Shutdown;
      else if (w[1] == "standby") ble_ = Ble::Standby;
      else if (w[1] == "connected") ble_ = Ble::Connected;
      else if (w[1] == "session") ble_ = Ble::Session;
      else throw std::invalid_argument("BLE state " + w[1]);
    } else if (k == "endstop") {
      need(4);
      const std::size_t a = axis_of(w[1]);
      const std::size_t side = w[2] == "min" ? 0 : 1;
      endstop_force_[a][side] = w[3] == "on" ? std::int8_t{1} : (w[3] == "off" ? std::int8_t{-1} : std::int8_t{0});
    } else if (k == "button") {
      need(2);
      button_ = true;
      button_until_us_ = now_us_ + (w[1] == "hold" ? 3'000'000 : 200'000);
    } else if (k == "reboot") {
      need(1);
      power_cycle_parts();
      powered_off_ = false;
      if (board_) boot();
    } else if (k == "encoder") {
      need(2);
      if (w[1] != "on" && w[1] != "off") throw std::invalid_argument("encoder on|off");
      encoder_fitted_ = w[1] == "on";
    } else {
      return "err unknown environment command '" + k + "'";
    }
    return "ok";
  } catch (const std::exception& e) {
    return std::string("err ") + e.what();
  }
}

void SimBoard::finish() {
  if (finished_) return;
  finished_ = true;
  if (on_qemu()) qemu_stop();
  if (opt_.out_dir.empty()) return;
  if (!opt_.qemu_image.empty()) write_qemu_stats();
  std::filesystem::create_directories(opt_.out_dir);
  // Lost-step risk per tick and axis, from the mechanics model over every STEP edge.
  std::array<std::vector<std::uint8_t>, xy_board::kAxes> risk;
  for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
    risk[a].assign(ticks_ + 1, 0);
    if (rec_[a].edges_ns.empty()) continue;
    const mech::Result res = mechanics(a);
    for (const mech::Sample& s : res.samples) {
      const auto k = static_cast<std::size_t>(std::max(0.0, std::floor(s.t * 1000.0)));
      if (k < risk[a].size()) risk[a][k] = std::max(risk[a][k], static_cast<std::uint8_t>(s.risk));
    }
  }
  {
    std::ofstream t(opt_.out_dir + "/trace.csv", std::ios::trunc);
    t << kTraceHeader
      << ",main_state,block,session,battery_mv,charger,usb,led,carriage_um,enc_turns,enc_counts,ena,link_alive,"
         "dispatched,gpio,lost_step_risk\n";
    for (std::size_t i = 0; i < trace_rows_.size(); ++i) {
      const std::size_t tick = i / xy_board::kAxes;
      const std::size_t a = i % xy_board::kAxes;
      t << trace_rows_[i] << ',' << mech::to_string(static_cast<mech::Risk>(risk[a][tick])) << '\n';
    }
  }
  {
    std::vector<wf::MotionTrace> traces;
    for (std::size_t a = 0; a < xy_board::kAxes; ++a) {
      wf::MotionTrace m;
      m.label.assign(1, a == 0 ? 'X' : 'Y');   // not operator=(const char*): gcc 12 -O3 -Wrestrict false positive
      m.t_s = plot_t_[a];
      m.pos_mm = plot_pos_[a];
      m.speed_mm_s = plot_v_[a];
      traces.push_back(std::move(m));
    }
    std::ofstream s(opt_.out_dir + "/plots.svg", std::ios::trunc);
    wf::write_motion_svg(s, "Board " + std::to_string(opt_.id) + ": position and speed", traces);
  }
  write_path_outputs();
  if (wave_) {
    wave_->finish();
    vcd_file_->flush();
  }
}

}  // namespace ap::sim::xy
