// The unit's firmware loop (unit.hpp; decisions in docs/unit3.md "The board").
#include "core/unit3/board/unit.hpp"

#include "core/unit3/joystick/joystick.hpp"

namespace ap::unit3_board {

namespace {

namespace r = unit3_ramp;
namespace w = unit3_wire;

// A refused plan: not a whole number of pulses, or past the counter's range. plan_move's other
// errors cannot come from here: the wire's 15 digits keep a count within TooFar's bound and the
// settings hold modes 0..5 only (unit3_settings), so they are reported as the range.
std::uint8_t refusal_code(unit3_axis::Error e) {
  return static_cast<std::uint8_t>(e == unit3_axis::Error::NotMultiple ? Refusal::NotMultiple : Refusal::CounterRange);
}

}  // namespace

const char* refusal_key(std::uint8_t code) {
  switch (code) {
    case static_cast<std::uint8_t>(Refusal::Busy): return "busy";
    case static_cast<std::uint8_t>(Refusal::NotMultiple): return "not_multiple";
    case static_cast<std::uint8_t>(Refusal::CounterRange): return "counter_range";
    case static_cast<std::uint8_t>(Refusal::Endstop): return "endstop";
    default: return nullptr;
  }
}

const char* source_key(Source s) {
  switch (s) {
    case Source::Idle: return "idle";
    case Source::Pc: return "pc";
    case Source::Joystick: return "joystick";
  }
  return "?";
}

Unit::Unit(std::span<std::uint8_t, unit3_settings::kImageSize> eeprom) : eeprom_(eeprom) {
  const auto l = unit3_settings::load(eeprom_);
  loaded_ = l.status;
  settings_ = l.settings;
  for (std::size_t a = 0; a < kAxes; ++a) {
    axes_[a].mode = settings_.mode[a];
    out_[a].mode = unit3_axis::kModePins[axes_[a].mode];
  }
}

void Unit::receive(std::uint8_t byte) {
  const auto e = framer_.push(byte);
  if (!e) return;
  if (!e->rejection.ok()) {
    send_error(static_cast<std::uint8_t>(e->rejection.error));
    return;
  }
  execute(e->command);
}

void Unit::execute(const w::Command& c) {
  switch (c.kind) {
    case w::Kind::Direction: dir_ = c.sign; return;
    case w::Kind::Move: start_move(static_cast<std::size_t>(c.axis), c.count); return;
    case w::Kind::StepMode:
      settings_.mode = c.digit;
      save_settings();
      send_settings(settings_);
      return;
    case w::Kind::Thread:
      settings_.thread = c.digit;
      save_settings();
      send_settings(settings_);
      return;
    case w::Kind::Clear:
      for (std::size_t a = 0; a < kAxes; ++a) {
        axes_[a].counter = 0;
        send_counter(a);
      }
      return;
    case w::Kind::Get: send_settings(unit3_settings::load(eeprom_).settings); return;  // what is stored [T §2.3]
  }
}

void Unit::start_move(std::size_t a, std::uint64_t count) {
  AxisState& s = axes_[a];
  if (s.source != Source::Idle) {
    send_error(static_cast<std::uint8_t>(Refusal::Busy));
    return;
  }
  const std::int8_t dir = dir_[a];
  if ((endstops_ & endstop_bit(a, dir > 0)) != 0) {
    send_error(static_cast<std::uint8_t>(Refusal::Endstop));
    return;
  }
  s.mode = settings_.mode[a];  // at rest: the pins may change
  const auto plan = unit3_axis::plan_move(s.counter, dir, count, s.mode);
  if (plan.error != unit3_axis::Error::None) {
    send_error(refusal_code(plan.error));
    return;
  }
  if (plan.pulses == 0) {  // nothing to run: the move is done as it is accepted
    send_counter(a);
    return;
  }
  s.source = Source::Pc;
  s.dir = dir;
  s.entry = 0;
  s.remaining = plan.pulses;
  s.interval_ms = 0;
  timers_[a].start(r::kTable.top[0]);
}

void Unit::press(unit3_menu::Button b) {
  switch (unit3_menu::press(menu_, settings_, b)) {
    case unit3_menu::Effect::None: return;
    case unit3_menu::Effect::Zero:
      for (std::size_t a = 0; a < kAxes; ++a) {
        axes_[a].counter = 0;
        send_counter(a);
      }
      return;
    case unit3_menu::Effect::Save:
      save_settings();
      send_settings(settings_);
      return;
  }
}

void Unit::tick(const Inputs& in) {
  endstops_ = in.endstops;
  ++now_ms_;
  for (std::size_t a = 0; a < kAxes; ++a) run_axis(a, in);
  if (now_ms_ % kReportMs == 0) {
    for (std::size_t a = 0; a < kAxes; ++a) {
      if (axes_[a].source != Source::Idle) send_counter(a);
    }
  }
}

void Unit::run_axis(std::size_t a, const Inputs& in) {
  AxisState& s = axes_[a];
  AxisOut& o = out_[a];
  o.pulses = 0;
  o.pulse_at = 0;
  // The stick drives the axes in the POSITIONS window only, where their positions are shown
  // (docs/unit3.md "The menu": the thesis drives the motors with the stick while the display
  // shows their positions, 001_*.txt:73-75, 1063-1067 and 1189-1195). In the other windows it
  // reads as centred: an axis it runs ramps down to entry 0 and stops, one at rest stays there.
  const auto stick = menu_.window == unit3_menu::Window::Positions ? unit3_joystick::deflection(in.adc[a])
                                                                    : unit3_joystick::Deflection{};
  const auto per = static_cast<std::int64_t>(unit3_axis::counts_per_pulse(s.mode));
  const auto in_range = [&](std::int8_t dir) {
    const std::int64_t next = s.counter + (dir > 0 ? per : -per);
    return next <= unit3_axis::kMaxCounter && next >= -unit3_axis::kMaxCounter;
  };
  if (s.source == Source::Idle) {
    s.mode = settings_.mode[a];
    if (stick.dir != 0 && (endstops_ & endstop_bit(a, stick.dir > 0)) == 0 && in_range(stick.dir)) {
      s.source = Source::Joystick;
      s.dir = stick.dir;
      s.entry = 0;
      s.interval_ms = 0;
      timers_[a].start(r::kTable.top[0]);
    }
  }
  if (s.source != Source::Idle) {
    if ((endstops_ & endstop_bit(a, s.dir > 0)) != 0) {
      if (s.source == Source::Pc) send_error(static_cast<std::uint8_t>(Refusal::Endstop));
      stop_axis(a);
    } else {
      if (s.interval_ms == r::kRampMs) {
        s.interval_ms = 0;
        const bool pc = s.source == Source::Pc;
        const auto next = pc ? r::next_entry(s.entry, r::kEntries - 1, false, s.remaining)
                             : r::next_entry(s.entry, stick.index, stick.dir != s.dir, r::kNoEnd);
        if (next.stop) {
          stop_axis(a);
        } else {
          s.entry = next.entry;
          timers_[a].set_top(r::kTable.top[s.entry]);
        }
      }
    }
  }
  if (s.source != Source::Idle) {
    ++s.interval_ms;
    std::uint32_t at = 0;
    if (timers_[a].advance(r::kTickClocks, at) > 0) {
      if (s.source == Source::Joystick && !in_range(s.dir)) {
        stop_axis(a);  // the counter's end: the stick cannot run it past what the unit reports
      } else {
        s.counter += s.dir > 0 ? per : -per;
        o.pulses = 1;
        o.pulse_at = static_cast<std::uint16_t>(at);
        if (s.source == Source::Pc && --s.remaining == 0) stop_axis(a);
      }
    }
  }
  o.dir = s.dir;
  o.mode = unit3_axis::kModePins[s.mode];
  o.running = s.source != Source::Idle;
}

void Unit::stop_axis(std::size_t a) {
  AxisState& s = axes_[a];
  s.source = Source::Idle;
  s.entry = 0;
  s.remaining = 0;
  s.interval_ms = 0;
  send_counter(a);
}

void Unit::save_settings() {
  std::array<std::uint8_t, unit3_settings::kImageSize> image{};
  if (!unit3_settings::store(settings_, image)) return;  // the menu and the wire keep them in range
  bool same = true;
  for (std::size_t i = 0; i < image.size(); ++i) same = same && image[i] == eeprom_[i];
  if (same) return;  // an EEPROM cell survives 100 000 writes: write only a change [D]
  for (std::size_t i = 0; i < image.size(); ++i) eeprom_[i] = image[i];
  ++eeprom_writes_;
}

void Unit::send_settings(const unit3_settings::Settings& s) {
  for (const auto kind : {w::Kind::StepMode, w::Kind::Thread}) {
    w::Command c;
    c.kind = kind;
    c.digit = kind == w::Kind::StepMode ? s.mode : s.thread;
    std::array<std::uint8_t, w::kMaxLine> line{};
    const std::size_t n = w::format(c, line);
    tx_.put(std::span<const std::uint8_t>(line.data(), n));
  }
}

void Unit::send_counter(std::size_t a) {
  std::array<std::uint8_t, w::kReportLength> line{};
  const std::size_t n = w::format_report(static_cast<w::Axis>(a), axes_[a].counter, line);
  tx_.put(std::span<const std::uint8_t>(line.data(), n));
}

void Unit::send_error(std::uint8_t code) {
  std::array<std::uint8_t, w::kErrorLength> line{};
  const std::size_t n = w::format_error(code, line);
  tx_.put(std::span<const std::uint8_t>(line.data(), n));
}

}  // namespace ap::unit3_board
