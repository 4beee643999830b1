// The simulated board (docs/sim.md): the real board core (core/xy/board, unchanged) over
// virtual peripherals. A test fixture, so it may use the heap and the device models:
//   two TMC2130 device models (SPI), the MB85RS256B FRAM model (SPI), two RLS Orbis absolute
//   encoders (14-bit position + turn count, read by eq. 7-2 at boot), four Hall endstops
//   driven by the carriage position (or forced), a GPIO expander that carries them, the BLE
//   module status pins (Tab. 7-2), the power module (battery mV, charger, USB flag, charge
//   current), the TMP117 and ICM-20789 device models on one I2C bus (the platform turned
//   through the gyro's rate), the user button and the RGB LED (Tab. 7-4), plus a carriage per
//   axis moved by the STEP/DIR/ENA outputs.
//
// Time is virtual: advance_to(t_us) runs 1 ms board ticks up to t. Everything the board sends
// on its UART TX line is queued and handed out by take_tx(). Harness-side commands (the
// "environment": battery, charger, pins, reboot, probes of the models) arrive as text through
// env(); docs/sim.md lists them. Outputs (trace.csv, waveforms.vcd, plots.svg) are optional.
//
// The drivers, the FRAM and the sensors are the device models every board fixture shares
// (sim/xy/rig/parts.hpp). SimBoard's code, one concern a file:
//   src/board.cpp          the core wired to the parts: its Hardware, boot, the tick, the checks
//                          run beside it (echo model, safety monitor, delivery digest)
//   src/board_physics.cpp  the machine around the parts: carriage, encoders, endstops, the
//                          input pins, the platform's turn, the mechanics model
//   src/board_outputs.cpp  the run's files: waveforms.vcd, trace.csv, plots.svg, path.csv
//   src/board_env.cpp      the text of env() and its probes
//   src/board_qemu.cpp     the QEMU target: the image's session and its transactions
//   src/board_mirror.cpp   the host core as the image's mirror, compared tick by tick
#pragma once

#include <array>
#include <map>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/xy/axis/watchdog.hpp"
#include "core/xy/board/board.hpp"
#include "models/xy/echo/board_checker.hpp"
#include "models/xy/safety/board_monitor.hpp"
#include "models/xy/mechanics/mechanics.hpp"
#include "sim/xy/digest.hpp"
#include "sim/xy/led.hpp"
#include "sim/xy/qemu_image.hpp"
#include "sim/xy/rig/parts.hpp"
#include "sim/xy/trace.hpp"

namespace ap::model::waveform {
class BoardWaveforms;
}

namespace ap::sim::xy {

// Physical constants of the simulated machine (docs/sim.md). The board's parameters may say
// otherwise (a wrong pitch stays wrong in µm, as on the real platform).
struct Machine {
  std::int32_t lead_um = 2000;            // screw lead per revolution (encoder: one turn)
  std::int32_t full_steps = 200;          // Tab. 4-1: 1.8 deg
  std::int32_t endstop_min_um = -2000;    // Hall switch positions (active at or beyond)
  std::int32_t endstop_max_um = 202'000;
};

struct BoardOptions {
  std::uint32_t id = 0;
  std::uint32_t baud = 115'200;
  std::string out_dir;         // empty: no output files
  bool waveforms = true;       // waveforms.vcd (with out_dir)
  // The QEMU target (docs/qemu.md): the image at this path runs the board; empty: the core
  // runs in this process.
  std::string qemu_image;
  std::string qemu_dir;        // its FIFOs, socket and log (default: out_dir/qemu or a temp dir)
};

// What the QEMU target measured (docs/qemu.md "The gate stage"), over all boots of a run.
struct QemuStats {
  std::uint64_t ticks = 0;          // control ticks the image ran
  double wall_s = 0;                // wall time spent running them
  std::uint32_t stack_used = 0;     // the highest stack high-water mark of any boot (bytes)
  std::uint32_t stack_size = 0;
  std::uint64_t boots = 0;
  std::uint64_t divergences = 0;    // ticks where the image and the host core disagreed
};

// Tab. 7-2 states of the BLE module status pins (STATUS1_IND, STATUS2_IND).
enum class Ble : std::uint8_t { Shutdown, Standby, Connected, Session };

// LED colours (bits 0..2 = R, G, B) and blink (bits 4..5: 0 steady, 1 slow, 2 fast), Tab. 7-4.
// (Its words in the scenario language: led_word, sim/xy/led.hpp.)
std::uint8_t led_code(const xy_board::Board& b);

struct Violation {
  std::int64_t t_us;
  int axis;
  std::string what;
};

class SimBoard {
 public:
  explicit SimBoard(BoardOptions opt);
  ~SimBoard();
  SimBoard(const SimBoard&) = delete;
  SimBoard& operator=(const SimBoard&) = delete;

  // Power-up. Called by the first advance_to()/rx() if not called before; setup env commands
  // (pos, endstop position, param, fram) only act before it.
  void boot();
  [[nodiscard]] bool booted() const { return board_ != nullptr; }
  // Runs board ticks until the virtual time reaches t_us (1 ms each).
  void advance_to(std::int64_t t_us);
  // Bytes arriving on the board's UART RX line now.
  void rx(std::span<const std::uint8_t> bytes);
  // Takes at most `max_bytes` of whole echo frames from the TX queue (the UART is slow: one
  // 65-byte echo takes 5.6 ms at 115200 baud).
  std::vector<std::uint8_t> take_tx(std::size_t max_bytes);
  // A harness command (docs/sim.md); returns "ok[ VALUE]" or "err WHY".
  std::string env(const std::string& line);
  // Ends the run: orderly outputs (trace, VCD, SVG), lost-step analysis.
  void finish();

  [[nodiscard]] std::int64_t now_us() const { return now_us_; }
  [[nodiscard]] const xy_board::Board& core() const { return *board_; }
  [[nodiscard]] Ble ble() const { return ble_; }
  [[nodiscard]] std::uint8_t led() const;
  [[nodiscard]] const std::vector<Violation>& violations() const { return violations_; }
  // Lost-step risks per axis from the mechanics model over all STEP edges so far.
  [[nodiscard]] std::size_t lost_step_risks(std::size_t a);
  [[nodiscard]] std::uint64_t ticks() const { return ticks_; }
  // The echo reference model (models/xy/echo) run beside the board core on every tick: the
  // disagreements found so far (at most 20 kept), how many there were and how many echoes
  // were compared. A fresh checker with fresh boot facts follows every boot (docs/sim.md).
  [[nodiscard]] const std::vector<std::string>& echo_disagreements() const { return echo_bad_; }
  [[nodiscard]] std::uint64_t echoes_checked() const { return echoes_checked_; }
  // Every echo the core sent on TX (all boots): count and FNV-1a 64 digest of the bytes in
  // order, for the PC's check that the bus delivered exactly these (probe `echo_sent`).
  [[nodiscard]] std::uint64_t echoes_sent() const { return echo_digests_.size(); }

 private:
  // A board tick in ns, the unit of the STEP edges and the waveforms' timestamps.
  static constexpr std::int64_t kNsPerTick = 1'000'000;
  // The waveforms' SPI devices (chip selects): TMC2130 X and Y, FRAM, encoders X and Y, the
  // GPIO expander.
  static constexpr std::size_t kDevTmcX = 0, kDevFram = 2, kDevEncX = 3, kDevExpander = 5;
  // The gyro's codes per °/s at ±250 °/s (DS-000169 Table 1); `rotate` counts in them.
  static constexpr std::int64_t kGyroLsbPerDps = 131;

  // The core wired to the parts (src/board.cpp). Hardware's callbacks; on the QEMU target
  // each one also holds the host core to what the image did (src/board_mirror.cpp).
  static void sample(void* ctx, xy_board::Inputs& in);
  static void motor(void* ctx, xy_board::Axis a, const xy_board::MotorOutput& o);
  static void uart_tx(void* ctx, std::span<const std::uint8_t> bytes);
  static void led_out(void* ctx, xy_board::LedColour lit);
  static void encoder_zero(void* ctx, xy_board::Axis a, std::int64_t counts);
  static void power_off(void* ctx);
  static void charger_enable(void* ctx, bool on);
  static void frame_taken(void* ctx, const xy_frame::CommandFrame& f);
  static bool tmc_spi(void* ctx, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx);
  static bool tmc_spi_y(void* ctx, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx);
  static bool fram_spi(void* ctx, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept;
  static xy_i2c::Status i2c_port(void* ctx, std::uint8_t address, std::span<const std::uint8_t> tx,
                              std::span<std::uint8_t> rx);
  bool tmc_transfer(std::size_t a, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx);
  xy_i2c::Status i2c_transfer(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx);
  // The device models' side of a transfer (the mirror's transfers replay the image's instead).
  bool tmc_device(std::size_t a, const xy_tmc2130::Datagram& tx, xy_tmc2130::Datagram& rx);
  bool fram_device(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept;
  // One transaction on the sensor bus (TMP117 at 0x48, ICM-20789 at 0x68).
  xy_i2c::Status i2c_device(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx);
  [[nodiscard]] model::xy_echo::Sensors sensors_now() const;
  void tx_effect(std::span<const std::uint8_t> bytes);
  void tick();
  void check_safety();
  void echo_disagreement(const std::string& what);
  void seed_fram();

  // The machine around the parts (src/board_physics.cpp).
  struct AxisRec {
    std::vector<std::int64_t> edges_ns;   // every STEP edge
    std::vector<std::int8_t> dirs;
  };
  void fill_inputs(xy_board::Inputs& in);
  std::uint16_t expander_word() const;
  std::uint16_t expander_word(const xy_board::Inputs& in) const;
  // Counts of the screw's angle from carriage 0, before the offset.
  std::int64_t encoder_raw_counts(std::size_t a) const;
  // The encoder programmed to read `counts` where the screw stands now (Hardware::encoder_zero).
  void zero_encoder(std::size_t a, std::int64_t counts);
  void motor_effect(std::size_t a, const xy_board::MotorOutput& o);
  // The platform's turn and the TMP117's clock, before each board tick (docs/sim.md "rotate").
  void sensors_tick();
  std::int32_t usteps_per_rev(std::size_t a) const;
  [[nodiscard]] model::xy_mechanics::Result mechanics(std::size_t a) const;

  // The run's files (src/board_outputs.cpp).
  void open_outputs();
  void wave_boot_encoders();
  void wave_motor(std::size_t a, std::int64_t t0_ns, const xy_board::MotorOutput& o, const std::vector<std::int64_t>& edges);
  void wave_expander();
  void trace_tick();
  void path_tick(double um_per_ustep);
  void write_path_outputs() const;
  void write_outputs();

  // The text of env() (src/board_env.cpp).
  std::string probe(const std::string& subject);

  // The QEMU target (docs/qemu.md "Co-simulation"; src/board_qemu.cpp, src/board_mirror.cpp).
  // The image runs the board; board_ below is its mirror: the host core fed the same inputs,
  // whose SPI transfers, motor outputs and TX bytes must equal the image's, tick by tick. The
  // image's transactions drive the device models; the mirror's are checked against them and
  // answered with the image's replies.
  struct Transfer {
    std::uint8_t dev = 0;
    std::vector<std::uint8_t> mosi, miso;
    std::uint8_t status = 0;  // I2C: how the transaction ended (xy_i2c::Status)
  };
  struct ImageMotor {
    bool dir = true;
    bool armed = false;
    std::uint16_t psc = 0, arr = 0;
    std::int32_t steps = 0;
  };
  [[nodiscard]] bool on_qemu() const { return qemu_ != nullptr; }
  void qemu_start();
  void qemu_stop();
  void qemu_serve(xy_cosim::Kind until, QemuImage::Message* last);
  void qemu_answer(const QemuImage::Message& m);
  void qemu_tick();
  void qemu_after_tick(bool boot);
  void qemu_fail(const std::string& what);
  bool replay(std::uint8_t dev, std::span<const std::uint8_t> mosi, std::span<std::uint8_t> miso);
  xy_i2c::Status replay_i2c(std::uint8_t address, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx);
  // The host core's outputs of a tick against the image's: the motor output (the image's,
  // where they differ, moves the carriage), the TX bytes (the image's go out), the LED, the
  // encoder programming, the charger enable and the KillSwitch.
  xy_board::MotorOutput mirror_motor(std::size_t a, const xy_board::MotorOutput& o);
  std::span<const std::uint8_t> mirror_tx(std::span<const std::uint8_t> bytes);
  void mirror_led(xy_board::LedColour lit);
  void mirror_encoder_zero(std::size_t a, std::int64_t counts);
  void mirror_charger(bool on);
  void mirror_kill();
  // I2C transfers share the log with SPI, keyed by this bit over the 7-bit address.
  static constexpr std::uint8_t kI2cLogKey = 0x80;
  void write_qemu_stats() const;
  std::unique_ptr<QemuImage> qemu_;
  bool image_ready_ = false;   // the image waits for a grant (its Ready was read)
  std::vector<Transfer> qemu_log_;
  std::size_t qemu_log_pos_ = 0;
  std::array<ImageMotor, xy_board::kAxes> image_motor_{};
  std::uint8_t image_olat_b_ = 0xC0;
  // The image's IODIRB: the MCP23S17 resets every pin to an input (0xFF); a pin left an input
  // drives nothing, and the board's pull-up holds DRV_ENN high (driver off; docs/qemu.md).
  std::uint8_t image_iodir_b_ = 0xFF;
  // The image's output pin `bit` of OLATB as it reaches the board: driven only as an output.
  bool image_pin_low(std::uint8_t bit) const { return (image_iodir_b_ & bit) == 0 && (image_olat_b_ & bit) == 0; }
  bool image_pin_high(std::uint8_t bit) const { return (image_iodir_b_ & bit) == 0 && (image_olat_b_ & bit) != 0; }
  std::vector<std::uint8_t> image_tx_;      // the image's TX bytes of this tick, not yet matched
  std::size_t image_tx_pos_ = 0;
  std::uint32_t link_delivered_ = 0;        // link bytes sent to the image since its power-up
  std::uint32_t image_ticks_ = 0;
  std::array<std::int32_t, xy_board::kAxes> image_pos_{};
  QemuStats qemu_stats_;

  BoardOptions opt_;
  Machine machine_;
  BoardParts parts_;   // the drivers, the FRAM and the sensor bus (sim/xy/rig/parts.hpp)
  std::unique_ptr<xy_board::Board> board_;
  std::int64_t now_us_ = 0;
  std::uint64_t ticks_ = 0;
  std::uint64_t boots_ = 0;

  // Environment.
  Ble ble_ = Ble::Session;
  bool usb_ = false;
  bool charger_ = false;
  std::uint16_t battery_mv_ = 4000;
  // The platform's rotation since the board's power-up, and where `rotate` turns it, in gyro
  // codes summed over ticks (1/131 m° at ±250 °/s; always whole m°, docs/sim.md).
  std::int64_t turned_codes_ = 0;
  std::int64_t turn_to_codes_ = 0;
  bool button_ = false;
  std::int64_t button_until_us_ = 0;
  std::array<std::array<std::int8_t, 2>, xy_board::kAxes> endstop_force_{};   // [axis][min,max]: -1 off, 0 auto, 1 on
  std::array<std::int32_t, xy_board::kAxes> endstop_min_um_{};
  std::array<std::int32_t, xy_board::kAxes> endstop_max_um_{};
  std::array<double, xy_board::kAxes> carriage_um_{};   // the physical carriage
  // The RLS Orbis's programmed offset, in counts (16384 a turn): what it subtracts from the
  // angle of the screw it measures. Kept in the encoder's own memory, so it survives a reboot
  // (thesis §7.7.2); 0 until the board programs one (the zero it left the factory with is
  // the screw at carriage 0).
  std::array<std::int64_t, xy_board::kAxes> encoder_offset_{};
  bool encoder_fitted_ = true;   // "encoder off": no valid reading (the FRAM counter path)
  bool powered_off_ = false;     // the core pulled the KillSwitch
  bool charging_enabled_ = true; // the core's charger enable (docs/board.md "Charger disconnect")
  bool button_at_off_ = false;   // the button's level at the last tick while switched off
  // The image's encoder programming requests of this tick, per axis (QEMU mirror).
  std::array<std::optional<std::int64_t>, xy_board::kAxes> image_encoder_zero_{};
  bool image_kill_ = false;      // the image's KillSwitch pin
  bool image_charger_ = true;    // the image's charger enable pin
  std::uint16_t expander_last_ = 0xFFFF;

  // Outputs and monitors.
  std::vector<std::uint8_t> tx_;
  std::array<AxisRec, xy_board::kAxes> rec_{};
  std::array<StepClock, xy_board::kAxes> clock_{};
  std::array<xy_board::MotorOutput, xy_board::kAxes> out_{};
  model::xy_safety::BoardMonitor monitor_;
  std::vector<model::xy_safety::Violation> found_;
  std::vector<Violation> violations_;
  std::vector<std::string> trace_rows_;
  std::array<std::vector<double>, xy_board::kAxes> plot_t_, plot_pos_, plot_v_;
  // The coordinated path (docs/cnc.md): path.csv and profile.svg, while a path runs.
  struct PathRow {
    double t_s = 0, x_mm = 0, y_mm = 0, carriage_x_mm = 0, carriage_y_mm = 0;
    double v = 0, a = 0, j = 0;  // the S-curve along the driving axis: mm/s, mm/s^2, mm/s^3
  };
  std::vector<PathRow> path_rows_;
  bool path_was_active_ = false;
  std::unique_ptr<std::ofstream> vcd_file_;
  std::unique_ptr<model::waveform::BoardWaveforms> wave_;
  std::array<bool, xy_board::kAxes> wave_dir_{};
  std::array<bool, xy_board::kAxes> wave_ena_{};
  bool finished_ = false;
  std::array<std::optional<std::size_t>, xy_board::kAxes> risk_cache_{};
  std::array<std::size_t, xy_board::kAxes> risk_cache_edges_{};
  std::vector<std::pair<std::string, std::int64_t>> preboot_params_;

  // Echo model check.
  std::unique_ptr<model::xy_echo::BoardChecker> checker_;
  std::vector<model::xy_echo::EchoBytes> tick_echoes_;   // what the core sent on TX in this tick
  std::vector<std::string> echo_bad_;
  xy_board::Inputs sampled_{};          // what the last sample() delivered
  std::uint64_t samples_ = 0;
  std::uint64_t echo_bad_count_ = 0;
  std::uint64_t echoes_checked_ = 0;
  // Every echo the core sent, over all boots: the FNV-1a digest of the whole TX stream after
  // each of them (docs/sim.md "Echo checks").
  std::vector<std::uint64_t> echo_digests_;
  std::uint64_t frames_taken_ = 0;
  std::map<std::uint16_t, model::xy_echo::FrameFate> fates_;  // by seq, the last frame taken with it
  std::uint64_t taken_digest_ = kFnvBasis;
};

}  // namespace ap::sim::xy
