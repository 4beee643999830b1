// Value Change Dump (IEEE 1364 §18) output of a simulated board, for GTKWave and PulseView.
//
// VcdWriter is generic: declare wires (scope path "board.x", name, width), record changes in any
// order, then flush(before) / finish() write them sorted by time (stable: same-time changes keep
// their call order). Redundant changes (same value) are dropped. Times are integers in the
// declared timescale (default 1 ns).
//
// BoardWaveforms declares the board's lines and turns events into edges:
//   board.<axis>.STEP/DIR/ENA     STEP pulse per microstep, DIR level, ENA = driver enabled
//                                  (logical; the TMC2130 DRV_ENN pin is its inverse)
//   board.spi.SCK/MOSI/MISO        one shared bus; board.spi.CS_<device> per device, active low;
//                                  MISO is 'z' while no CS is low; MSB first; per-device CPOL/CPHA
//   board.uart.RX/TX               MCU view: RX = PC -> board (commands), TX = board -> PC
//                                  (echoes); 8N1: start bit, 8 data bits LSB first, stop bit
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ap::model::waveform {

// 1-bit special values.
inline constexpr std::uint64_t kHighZ = ~std::uint64_t{0};
inline constexpr std::uint64_t kUnknown = ~std::uint64_t{0} - 1;

class VcdWriter {
 public:
  struct Options {
    std::string timescale = "1ns";
    std::string version = "axisproof models/waveform";
    std::string comment;
  };
  explicit VcdWriter(std::ostream& os) : VcdWriter(os, Options{}) {}
  VcdWriter(std::ostream& os, Options opt);

  // Declares a wire; only before the first flush. Returns its handle.
  int wire(std::string_view scope, std::string_view name, unsigned width = 1, std::uint64_t initial = 0);
  // Records a change. Throws std::logic_error when t is before the flushed watermark.
  void set(std::uint64_t t, int signal, std::uint64_t value);
  // Writes the header (once) and all changes with time < before.
  void flush(std::uint64_t before);
  // Writes everything left; later set() calls throw.
  void finish();
  [[nodiscard]] std::size_t pending() const { return events_.size(); }

 private:
  struct Var {
    std::string scope, name, id;
    unsigned width;
    std::uint64_t initial, current;
  };
  struct Event {
    std::uint64_t t;
    std::uint64_t order;
    int signal;
    std::uint64_t value;
  };
  void header();
  void emit_value(const Var& v, std::uint64_t value);

  std::ostream& os_;
  Options opt_;
  std::vector<Var> vars_;
  std::vector<Event> events_;
  std::uint64_t order_ = 0;
  std::uint64_t watermark_ = 0;
  std::uint64_t last_time_written_ = 0;
  bool header_done_ = false;
  bool time_written_ = false;
  bool finished_ = false;
};

struct SpiDevice {
  std::string name;
  bool cpol = true;   // TMC2130: SPI mode 3
  bool cpha = true;
};

struct BoardWaveformConfig {
  std::vector<std::string> axes{"x", "y"};
  std::vector<SpiDevice> spi_devices{{"tmc_x", true, true}, {"tmc_y", true, true}, {"fram", false, false},
                                     {"enc_x", false, true}, {"enc_y", false, true}, {"expander", false, false}};
  std::uint32_t spi_hz = 1'000'000;
  std::uint32_t uart_baud = 115'200;
  std::uint64_t step_pulse_ns = 2'000;   // STEP high time
};

// All times in ns (the writer's timescale is 1 ns).
class BoardWaveforms {
 public:
  enum class Uart { rx, tx };
  BoardWaveforms(std::ostream& os, BoardWaveformConfig cfg);

  void step(std::size_t axis, std::uint64_t t);
  void dir(std::size_t axis, std::uint64_t t, bool level);
  void ena(std::size_t axis, std::uint64_t t, bool enabled);
  // A full-duplex transfer with `device` starting at t (or when the bus is free); mosi and miso
  // the same length (miso may be empty: reads as 0). Returns the time CS goes high again.
  std::uint64_t spi(std::size_t device, std::uint64_t t, std::span<const std::uint8_t> mosi,
                    std::span<const std::uint8_t> miso = {});
  // Bytes on a UART line from t (or when the line is free); returns the end of the last stop bit.
  std::uint64_t uart(Uart line, std::uint64_t t, std::span<const std::uint8_t> bytes);
  [[nodiscard]] std::size_t spi_device(std::string_view name) const;   // throws if unknown
  [[nodiscard]] const BoardWaveformConfig& config() const { return cfg_; }

  void flush(std::uint64_t before) { w_.flush(before); }
  void finish() { w_.finish(); }

 private:
  BoardWaveformConfig cfg_;
  VcdWriter w_;
  std::vector<int> step_, dir_, ena_, cs_;
  int sck_ = -1, mosi_ = -1, miso_ = -1, rx_ = -1, tx_ = -1;
  std::uint64_t spi_free_ = 0, rx_free_ = 0, tx_free_ = 0;
};

// ---- reading VCD back (tests, checks of run outputs) -----------------------------------------

class VcdParseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct VcdDoc {
  struct Var {
    std::string type, id, scope, name;   // scope: dotted path
    unsigned width = 1;
  };
  struct Change {
    std::uint64_t t;
    std::string id;
    std::string value;   // "0", "1", "z", "x" for 1-bit; binary digits for vectors
  };
  std::string timescale;
  std::vector<Var> vars;
  std::vector<Change> changes;   // $dumpvars initial values at their time, then in file order

  [[nodiscard]] const Var* find(std::string_view scope, std::string_view name) const;
  // The (time, level) transitions of a 1-bit var, first entry = initial value.
  [[nodiscard]] std::vector<std::pair<std::uint64_t, char>> trace(std::string_view id) const;
};

// Parses and validates: every header section closed by $end, $enddefinitions present, ids
// declared once, value widths match, times strictly increasing. Throws VcdParseError.
VcdDoc parse_vcd(std::istream& in);
VcdDoc parse_vcd(std::string_view text);

// Decodes 8N1 frames from a line's trace (ns times) at `baud`; throws VcdParseError on a
// framing error (stop bit low).
std::vector<std::uint8_t> decode_uart(const std::vector<std::pair<std::uint64_t, char>>& line, std::uint32_t baud);

struct SpiTransfer {
  std::uint64_t t;
  std::vector<std::uint8_t> mosi, miso;
};
// Decodes the transfers of one CS line (sampling on the edge given by cpol/cpha).
std::vector<SpiTransfer> decode_spi(const VcdDoc& doc, std::string_view cs_id, bool cpol, bool cpha);

}  // namespace ap::model::waveform
