// The unit3 run's safety properties (sim/unit3/safety.hpp, docs/unit3-sim.md "Safety checks").
#include "sim/unit3/safety.hpp"

#include <cstdlib>

namespace ap::sim::unit3 {

namespace {

const char* const kAxisName[kAxes] = {"X", "Y", "Z"};

std::uint8_t mode_number(const unit3_axis::ModePins& p) {
  return static_cast<std::uint8_t>((p.m2 ? 4U : 0U) | (p.m1 ? 2U : 0U) | (p.m0 ? 1U : 0U));
}

}  // namespace

TickSample sample_of(const unit3_board::Unit& u, std::uint64_t t_ms, std::uint8_t endstops) {
  TickSample s;
  s.t_ms = t_ms;
  s.endstops = endstops;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const unit3_board::AxisState& st = u.axis(a);
    const unit3_board::AxisOut& o = u.out(a);
    AxisSample& x = s.axis[a];
    x.source = st.source;
    x.entry = st.entry;
    x.dir = o.dir;
    x.mode = mode_number(o.mode);
    x.counter = st.counter;
    x.remaining = st.remaining;
    x.pulses = o.pulses;
    x.pulse_at = o.pulse_at;
    x.running = o.running;
  }
  return s;
}

void SafetyChecker::fail(const TickSample& s, std::size_t a, const std::string& what) {
  violations_.push_back("t=" + std::to_string(s.t_ms) + " ms axis " + kAxisName[a] + ": " + what);
}

void SafetyChecker::power_cycle() { track_ = {}; }

void SafetyChecker::check(const TickSample& s) {
  ++ticks_;
  const auto tick_start = static_cast<std::int64_t>(s.t_ms - 1) * kTickClocks;
  const auto tick_end = static_cast<std::int64_t>(s.t_ms) * kTickClocks;
  for (std::size_t a = 0; a < kAxes; ++a) {
    const AxisSample& cur = s.axis[a];
    Track& tr = track_[a];
    const bool pulsed = cur.pulses > 0;
    const std::int64_t pulse_clock = tick_start + cur.pulse_at;

    // endstop: the switch ahead of the DIR pin is closed in this tick.
    if (pulsed && (s.endstops & unit3_board::endstop_bit(a, cur.dir > 0)) != 0) {
      fail(s, a, std::string("STEP pulse towards the closed ") + (cur.dir > 0 ? "max" : "min") + " endstop");
    }

    if (cur.running) {
      if (!tr.running) {
        // A start. reverse: from rest, the last stop must have been a controlled one.
        if (tr.stopped && cur.dir != tr.stop_dir && !tr.stop_ok) {
          fail(s, a, "DIR reversed after a stop from ramp entry " + std::to_string(tr.stop_entry) +
                         " (not decelerated to entry 0)");
        }
        // ramp: every motion starts at the start speed.
        if (cur.entry != 0) fail(s, a, "started at ramp entry " + std::to_string(cur.entry) + ", not 0");
        tr.last_change = s.t_ms;
        tr.last_clock = tick_start;
      } else {
        if (cur.dir != tr.dir && tr.entry != 0) {
          fail(s, a, "DIR reversed while running at ramp entry " + std::to_string(tr.entry));
        }
        if (cur.entry != tr.entry) {
          if (std::abs(static_cast<int>(cur.entry) - static_cast<int>(tr.entry)) > 1) {
            fail(s, a, "ramp entry jumped from " + std::to_string(tr.entry) + " to " + std::to_string(cur.entry));
          }
          if (s.t_ms - tr.last_change < static_cast<std::uint64_t>(kRampTicks)) {
            fail(s, a, "ramp entry changed " + std::to_string(s.t_ms - tr.last_change) +
                           " ms after the last change (one entry per " + std::to_string(kRampTicks) + " ms)");
          }
          tr.last_change = s.t_ms;
        }
      }
      // gap: the next pulse is due within one entry-0 period.
      const std::int64_t deadline = tr.last_clock + kSlowestPeriod;
      if (pulsed) {
        if (pulse_clock > deadline) {
          fail(s, a, "a gap of " + std::to_string(pulse_clock - tr.last_clock) + " timer clocks between pulses (at most " +
                         std::to_string(kSlowestPeriod) + ")");
        }
        tr.last_clock = pulse_clock;
      } else if (tick_end >= deadline) {
        fail(s, a, "running without a pulse for " + std::to_string(tick_end - tr.last_clock) + " timer clocks (at most " +
                       std::to_string(kSlowestPeriod) + ")");
        tr.last_clock = tick_end;  // one report per gap
      }
    } else if (tr.running) {
      // The axis stopped in this tick.
      const bool by_endstop = (s.endstops & unit3_board::endstop_bit(a, tr.dir > 0)) != 0;
      bool ok = tr.entry == 0;
      if (pulsed) {
        const std::int64_t gap = pulse_clock - tr.last_clock;
        if (gap > kSlowestPeriod) {
          fail(s, a, "a gap of " + std::to_string(gap) + " timer clocks before the last pulse (at most " +
                         std::to_string(kSlowestPeriod) + ")");
        }
        if (tr.source == unit3_board::Source::Pc && cur.remaining == 0) {
          // stop: a PC move's last pulse at the entry-0 period.
          ok = gap >= kSlowestPeriod;
          if (!ok) {
            fail(s, a, "the PC move's last pulse came " + std::to_string(gap) + " timer clocks after the one before: not at entry 0 (" +
                           std::to_string(kSlowestPeriod) + ")");
          }
        }
      }
      tr.stopped = true;
      tr.stop_ok = ok || by_endstop;
      tr.stop_dir = tr.dir;
      tr.stop_entry = tr.entry;
    }
    tr.running = cur.running;
    tr.dir = cur.dir;
    tr.entry = cur.entry;
    tr.source = cur.source;
  }
}

}  // namespace ap::sim::unit3
