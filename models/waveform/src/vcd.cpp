// VcdWriter and BoardWaveforms (see vcd.hpp).
#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "models/waveform/vcd.hpp"

namespace ap::model::waveform {
namespace {

std::string make_id(std::size_t n) {
  // Printable ASCII '!'..'~' without '#' and '$' (92 symbols; a lone '#' or '$' token confuses
  // some readers: timestamps and keywords), little-endian base 92.
  static constexpr std::string_view kAlphabet =
      "!\"%&'()*+,-./0123456789:;<=>?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_`abcdefghijklmnopqrstuvwxyz{|}~";
  static_assert(kAlphabet.size() == 92);
  std::string id;
  do {
    id.push_back(kAlphabet[n % kAlphabet.size()]);
    n /= kAlphabet.size();
  } while (n != 0);
  return id;
}

std::vector<std::string> split_scope(std::string_view scope) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= scope.size()) {
    const std::size_t dot = scope.find('.', start);
    const std::size_t end = dot == std::string_view::npos ? scope.size() : dot;
    if (end > start) {
      out.emplace_back(scope.substr(start, end - start));
    }
    if (dot == std::string_view::npos) {
      break;
    }
    start = dot + 1;
  }
  return out;
}

bool valid_name(std::string_view s) {
  return !s.empty() && std::none_of(s.begin(), s.end(), [](char c) { return c <= ' ' || c > '~' || c == '$'; });
}

}  // namespace

VcdWriter::VcdWriter(std::ostream& os, Options opt) : os_(os), opt_(std::move(opt)) {}

int VcdWriter::wire(std::string_view scope, std::string_view name, unsigned width, std::uint64_t initial) {
  if (header_done_) {
    throw std::logic_error("vcd: wire declared after the header was written");
  }
  if (!valid_name(name) || width == 0 || width > 64) {
    throw std::invalid_argument("vcd: bad wire " + std::string(name));
  }
  for (const std::string& part : split_scope(scope)) {
    if (!valid_name(part)) {
      throw std::invalid_argument("vcd: bad scope " + std::string(scope));
    }
  }
  vars_.push_back(Var{std::string(scope), std::string(name), make_id(vars_.size()), width, initial, initial});
  return static_cast<int>(vars_.size() - 1);
}

void VcdWriter::set(std::uint64_t t, int signal, std::uint64_t value) {
  if (finished_) {
    throw std::logic_error("vcd: set() after finish()");
  }
  if (signal < 0 || static_cast<std::size_t>(signal) >= vars_.size()) {
    throw std::out_of_range("vcd: unknown signal");
  }
  if (header_done_ && t < watermark_) {
    throw std::logic_error("vcd: change at " + std::to_string(t) + " is before the flushed time " +
                           std::to_string(watermark_));
  }
  events_.push_back(Event{t, order_++, signal, value});
}

void VcdWriter::emit_value(const Var& v, std::uint64_t value) {
  if (v.width == 1) {
    const char c = value == kHighZ ? 'z' : value == kUnknown ? 'x' : (value & 1U) != 0 ? '1' : '0';
    os_ << c << v.id << '\n';
    return;
  }
  std::string bits;
  for (unsigned i = v.width; i-- > 0;) {
    bits.push_back(((value >> i) & 1U) != 0 ? '1' : '0');
  }
  const std::size_t first = std::min(bits.find('1'), bits.size() - 1);
  os_ << 'b' << bits.substr(first) << ' ' << v.id << '\n';
}

void VcdWriter::header() {
  if (header_done_) {
    return;
  }
  header_done_ = true;
  os_ << "$version " << opt_.version << " $end\n";
  if (!opt_.comment.empty()) {
    os_ << "$comment " << opt_.comment << " $end\n";
  }
  os_ << "$timescale " << opt_.timescale << " $end\n";
  // Group vars by scope in order of first appearance.
  std::vector<std::string> scopes;
  for (const Var& v : vars_) {
    if (std::find(scopes.begin(), scopes.end(), v.scope) == scopes.end()) {
      scopes.push_back(v.scope);
    }
  }
  std::vector<std::string> open;
  for (const std::string& s : scopes) {
    const std::vector<std::string> want = split_scope(s);
    std::size_t common = 0;
    while (common < open.size() && common < want.size() && open[common] == want[common]) {
      ++common;
    }
    while (open.size() > common) {
      os_ << "$upscope $end\n";
      open.pop_back();
    }
    for (std::size_t i = common; i < want.size(); ++i) {
      os_ << "$scope module " << want[i] << " $end\n";
      open.push_back(want[i]);
    }
    for (const Var& v : vars_) {
      if (v.scope == s) {
        os_ << "$var wire " << v.width << ' ' << v.id << ' ' << v.name << " $end\n";
      }
    }
  }
  while (!open.empty()) {
    os_ << "$upscope $end\n";
    open.pop_back();
  }
  os_ << "$enddefinitions $end\n#0\n$dumpvars\n";
  for (const Var& v : vars_) {
    emit_value(v, v.initial);
  }
  os_ << "$end\n";
  time_written_ = true;
  last_time_written_ = 0;
}

void VcdWriter::flush(std::uint64_t before) {
  if (finished_) {
    return;
  }
  header();
  auto split = std::stable_partition(events_.begin(), events_.end(), [&](const Event& e) { return e.t < before; });
  std::vector<Event> now(events_.begin(), split);
  events_.erase(events_.begin(), split);
  std::sort(now.begin(), now.end(), [](const Event& a, const Event& b) {
    return a.t != b.t ? a.t < b.t : a.order < b.order;
  });
  for (const Event& e : now) {
    Var& v = vars_[static_cast<std::size_t>(e.signal)];
    const std::uint64_t value = v.width < 64 && e.value != kHighZ && e.value != kUnknown
                                    ? e.value & ((std::uint64_t{1} << v.width) - 1)
                                    : e.value;
    if (value == v.current) {
      continue;
    }
    if (!(time_written_ && e.t == last_time_written_)) {
      os_ << '#' << e.t << '\n';
      time_written_ = true;
      last_time_written_ = e.t;
    }
    emit_value(v, value);
    v.current = value;
  }
  watermark_ = std::max(watermark_, before);
}

void VcdWriter::finish() {
  if (finished_) {
    return;
  }
  std::uint64_t last = watermark_;
  for (const Event& e : events_) {
    last = std::max(last, e.t + 1);
  }
  flush(last);
  os_.flush();
  finished_ = true;
}

// ------------------------------------------------------------------------------ BoardWaveforms

BoardWaveforms::BoardWaveforms(std::ostream& os, BoardWaveformConfig cfg)
    : cfg_(std::move(cfg)), w_(os, VcdWriter::Options{"1ns", "axisproof models/waveform", "simulated board"}) {
  if (cfg_.spi_hz == 0 || cfg_.uart_baud == 0 || cfg_.step_pulse_ns == 0) {
    throw std::invalid_argument("waveform: zero clock, baud or pulse width");
  }
  for (const std::string& a : cfg_.axes) {
    const std::string scope = "board." + a;
    step_.push_back(w_.wire(scope, "STEP"));
    dir_.push_back(w_.wire(scope, "DIR"));
    ena_.push_back(w_.wire(scope, "ENA"));
  }
  const bool idle_sck = cfg_.spi_devices.empty() || cfg_.spi_devices.front().cpol;
  sck_ = w_.wire("board.spi", "SCK", 1, idle_sck ? 1 : 0);
  mosi_ = w_.wire("board.spi", "MOSI");
  miso_ = w_.wire("board.spi", "MISO", 1, kHighZ);
  for (const SpiDevice& d : cfg_.spi_devices) {
    cs_.push_back(w_.wire("board.spi", "CS_" + d.name, 1, 1));
  }
  rx_ = w_.wire("board.uart", "RX", 1, 1);
  tx_ = w_.wire("board.uart", "TX", 1, 1);
}

void BoardWaveforms::step(std::size_t axis, std::uint64_t t) {
  w_.set(t, step_.at(axis), 1);
  w_.set(t + cfg_.step_pulse_ns, step_.at(axis), 0);
}

void BoardWaveforms::dir(std::size_t axis, std::uint64_t t, bool level) { w_.set(t, dir_.at(axis), level ? 1 : 0); }

void BoardWaveforms::ena(std::size_t axis, std::uint64_t t, bool enabled) {
  w_.set(t, ena_.at(axis), enabled ? 1 : 0);
}

std::size_t BoardWaveforms::spi_device(std::string_view name) const {
  for (std::size_t i = 0; i < cfg_.spi_devices.size(); ++i) {
    if (cfg_.spi_devices[i].name == name) {
      return i;
    }
  }
  throw std::out_of_range("waveform: no SPI device " + std::string(name));
}

std::uint64_t BoardWaveforms::spi(std::size_t device, std::uint64_t t, std::span<const std::uint8_t> mosi,
                                  std::span<const std::uint8_t> miso) {
  const SpiDevice& d = cfg_.spi_devices.at(device);
  if (!miso.empty() && miso.size() != mosi.size()) {
    throw std::invalid_argument("waveform: MOSI and MISO lengths differ");
  }
  const std::uint64_t h = std::max<std::uint64_t>(1, 500'000'000ULL / cfg_.spi_hz);   // half period
  const std::uint64_t idle = d.cpol ? 1 : 0;
  const std::uint64_t t0 = std::max(t, spi_free_);
  w_.set(t0, sck_, idle);
  const std::uint64_t cs_low = t0 + h;
  w_.set(cs_low, cs_.at(device), 0);
  const std::size_t bits = mosi.size() * 8;
  auto bit_of = [](std::span<const std::uint8_t> bytes, std::size_t i) -> std::uint64_t {
    if (bytes.empty()) {
      return 0;
    }
    return (bytes[i / 8] >> (7 - i % 8)) & 1U;
  };
  for (std::size_t i = 0; i < bits; ++i) {
    const std::uint64_t lead = cs_low + h + 2 * h * i;
    const std::uint64_t trail = lead + h;
    const std::uint64_t data_at = d.cpha ? lead : (i == 0 ? cs_low : lead - h);
    w_.set(data_at, mosi_, bit_of(mosi, i));
    w_.set(data_at, miso_, bit_of(miso, i));
    w_.set(lead, sck_, 1 - idle);
    w_.set(trail, sck_, idle);
  }
  const std::uint64_t cs_high = cs_low + h + 2 * h * bits + h;
  w_.set(cs_high, cs_.at(device), 1);
  w_.set(cs_high, miso_, kHighZ);
  spi_free_ = cs_high + h;
  return cs_high;
}

std::uint64_t BoardWaveforms::uart(Uart line, std::uint64_t t, std::span<const std::uint8_t> bytes) {
  const int sig = line == Uart::rx ? rx_ : tx_;
  std::uint64_t& free_at = line == Uart::rx ? rx_free_ : tx_free_;
  const std::uint64_t t0 = std::max(t, free_at);
  // Edges from the start of the message, so rounding never accumulates over bytes.
  std::uint64_t bit_index = 0;
  const std::uint64_t baud = cfg_.uart_baud;
  auto edge = [&](std::uint64_t k) { return t0 + (k * 1'000'000'000ULL + baud / 2) / baud; };
  for (const std::uint8_t b : bytes) {
    w_.set(edge(bit_index), sig, 0);   // start bit
    for (unsigned k = 0; k < 8; ++k) {
      w_.set(edge(bit_index + 1 + k), sig, (b >> k) & 1U);
    }
    w_.set(edge(bit_index + 9), sig, 1);   // stop bit
    bit_index += 10;
  }
  const std::uint64_t end = edge(bit_index);
  free_at = end;
  return end;
}

}  // namespace ap::model::waveform
