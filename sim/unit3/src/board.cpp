// The unit3 simulated board and its bus side (sim/unit3/unit3.hpp, docs/unit3-sim.md "The board").
#include <algorithm>
#include <filesystem>
#include <span>
#include <sstream>

#include "sim/unit3/unit3.hpp"

namespace ap::sim::unit3 {

namespace {

std::optional<std::size_t> axis_of(const std::string& w) {
  if (w == "x") return 0;
  if (w == "y") return 1;
  if (w == "z") return 2;
  return std::nullopt;
}

std::optional<unit3_menu::Button> button_of(const std::string& w) {
  using B = unit3_menu::Button;
  if (w == "enter") return B::Enter;
  if (w == "back") return B::Back;
  if (w == "up") return B::Up;
  if (w == "down") return B::Down;
  if (w == "left") return B::Left;
  if (w == "right") return B::Right;
  return std::nullopt;
}

}  // namespace

Board::Board(const BoardOptions& opt) : opt_(opt) {
  if (opt.eeprom == Eeprom::Blank) {
    eeprom_.fill(0xFF);
  } else {
    unit3_settings::store(unit3_settings::kDefaults, eeprom_);
  }
  unit_.emplace(std::span<std::uint8_t, unit3_settings::kImageSize>(eeprom_));
}

void Board::advance_to(std::int64_t t_us) {
  while (static_cast<std::int64_t>(t_ms_ + 1) * 1000 <= t_us) tick();
}

void Board::tick() {
  const std::uint64_t m = t_ms_ + 1;
  const auto begin = static_cast<std::int64_t>(t_ms_) * 1000 * kLineUnitsPerUs;
  const std::int64_t end = begin + 1000 * kLineUnitsPerUs;
  // The UART transmitter sends what the unit queued before this ms, back to back, one byte per
  // 520.83 us: every byte that starts within this ms leaves the unit's reply queue now
  // (core/unit3/board/replies.hpp holds the rest) and reaches the PC when its stop bit ends.
  for (;;) {
    const std::int64_t start = std::max(tx_free_, begin);
    if (start >= end) break;
    std::array<std::uint8_t, 1> b{};
    if (unit_->take_tx(b) == 0) break;
    tx_free_ = start + kByteUnits;
    tx_line_.emplace_back(tx_free_, b[0]);
  }
  // The receiver: every byte whose stop bit ends within this ms reaches receive() before the
  // main-loop pass (the UART interrupt runs ahead of the loop).
  while (!rx_line_.empty() && rx_line_.front().first <= end) {
    unit_->receive(rx_line_.front().second);
    rx_line_.pop_front();
  }
  in_.endstops = unit3_board::endstops_from_pins(endstop_pins_);
  unit_->tick(in_);
  t_ms_ = m;
  const TickSample s = sample_of(*unit_, m, in_.endstops);
  for (std::size_t a = 0; a < kAxes; ++a) pulses_[a] += s.axis[a].pulses;
  checker_.check(s);
  samples_.push_back(s);
}

void Board::rx(const std::vector<std::uint8_t>& bytes, std::int64_t t_us) {
  std::int64_t at = std::max({rx_free_, static_cast<std::int64_t>(t_ms_) * 1000 * kLineUnitsPerUs, t_us * kLineUnitsPerUs});
  for (const std::uint8_t b : bytes) {
    at += kByteUnits;
    rx_line_.emplace_back(at, b);
  }
  rx_free_ = at;
}

std::vector<std::uint8_t> Board::take_tx(std::size_t max) {
  std::vector<std::uint8_t> out;
  const auto now = static_cast<std::int64_t>(t_ms_) * 1000 * kLineUnitsPerUs;
  while (!tx_line_.empty() && tx_line_.front().first <= now && out.size() < max) {
    out.push_back(tx_line_.front().second);
    tx_line_.pop_front();
  }
  return out;
}

std::string Board::state_of(std::size_t a) const {
  const unit3_board::AxisState& st = unit_->axis(a);
  const unit3_board::AxisOut& o = unit_->out(a);
  std::ostringstream r;
  r << "pulses=" << pulses_[a] << " counter=" << st.counter << " entry=" << static_cast<unsigned>(st.entry)
    << " dir=" << static_cast<int>(o.dir) << " running=" << (o.running ? 1 : 0) << " remaining=" << st.remaining
    << " mode=" << static_cast<unsigned>(st.mode) << " source=" << unit3_board::source_key(st.source);
  return r.str();
}

std::string Board::env(const std::string& line) {
  std::istringstream in(line);
  std::string verb, a1, a2, a3;
  in >> verb >> a1 >> a2 >> a3;
  if (verb == "joystick") {
    const auto a = axis_of(a1);
    if (!a || a2.empty() || a2.find_first_not_of("0123456789") != std::string::npos || a2.size() > 5) return "error joystick AXIS ADC";
    const unsigned long v = std::stoul(a2);
    if (v > 65535) return "error ADC value past 16 bits";
    in_.adc[*a] = static_cast<std::uint16_t>(v);
    return "ok";
  }
  if (verb == "endstop") {
    const auto a = axis_of(a1);
    if (!a || (a2 != "min" && a2 != "max") || (a3 != "on" && a3 != "off")) return "error endstop AXIS min|max on|off";
    // "on" closes the switch: its pin goes low (active low, unit3_board::endstops_from_pins).
    const std::uint8_t bit = unit3_board::endstop_bit(*a, a2 == "max");
    endstop_pins_ = a3 == "on" ? static_cast<std::uint8_t>(endstop_pins_ & ~bit) : static_cast<std::uint8_t>(endstop_pins_ | bit);
    return "ok";
  }
  if (verb == "press") {
    const auto b = button_of(a1);
    if (!b) return "error press enter|back|up|down|left|right";
    unit_->press(*b);
    return "ok";
  }
  if (verb == "power-cycle") {
    // Power lost: the motors stop, the reply queue and the counters are gone, the EEPROM
    // image stays (seed 001 §3.1: positions are 0 at power-on, the settings persist §3.8).
    tx_dropped_ += unit_->tx_dropped();
    unit_.emplace(std::span<std::uint8_t, unit3_settings::kImageSize>(eeprom_));
    checker_.power_cycle();
    ++power_cycles_;
    return "ok";
  }
  if (verb == "state") {
    const auto a = axis_of(a1);
    if (!a) return "error state AXIS";
    return state_of(*a);
  }
  if (verb == "summary") {
    std::ostringstream r;
    r << "ticks=" << checker_.ticks() << " violations=" << checker_.violations().size()
      << " dropped=" << (tx_dropped_ + unit_->tx_dropped()) << " power_cycles=" << power_cycles_
      << " pulses=" << pulses_[0] << "," << pulses_[1] << "," << pulses_[2];
    return r.str();
  }
  if (verb == "violation") return violation_reply(checker_.violations(), a1);
  return "error unknown environment command '" + verb + "'";
}

void Board::finish() { write_board_outputs(opt_.out_dir, samples_); }

int serve_board(const dds::ParticipantPtr& participant, const BoardOptions& opt, std::chrono::milliseconds idle_timeout,
                const std::atomic<bool>* stop) {
  return serve_unit_board<Board>(participant, opt, idle_timeout, stop, [](Board& board, const dds::CommandSample& cmd) {
    board.advance_to(static_cast<std::int64_t>(cmd.vtime_us));
    if (!cmd.bytes.empty()) board.rx(cmd.bytes, static_cast<std::int64_t>(cmd.vtime_us));
    return board.take_tx(dds::kFrameMax);
  });
}

}  // namespace ap::sim::unit3
