// The hc08 run's safety properties (sim/hc08/safety.hpp, docs/hc08-sim.md "Safety checks").
#include "sim/hc08/safety.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace ap::sim::hc08 {

namespace {

// The half-step table of docs/hc08.md "Excitation", in rotational order.
constexpr std::array<std::uint8_t, 8> kHalfTable = {0b0001, 0b0011, 0b0010, 0b0110, 0b0100, 0b1100, 0b1000, 0b1001};

std::string bits(std::uint8_t c) {
  std::string s;
  for (int b = 3; b >= 0; --b) s += ((c >> b) & 1U) != 0 ? '1' : '0';
  return s;
}

std::string hz_of(std::int64_t interval_units) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f Hz", static_cast<double>(kUnitsPerSecond) / static_cast<double>(interval_units));
  return buf;
}

std::string ticks_of(std::int64_t units) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", static_cast<double>(units) / static_cast<double>(kUnitsPerTick));
  return buf;
}

}  // namespace

std::optional<int> half_position(std::uint8_t coils) {
  for (std::size_t i = 0; i < kHalfTable.size(); ++i) {
    if (kHalfTable[i] == coils) return static_cast<int>(i);
  }
  return std::nullopt;
}

int half_steps(std::uint8_t from, std::uint8_t to) {
  const std::optional<int> a = half_position(from), b = half_position(to);
  if (!a || !b) return 0;
  const int d = ((*b - *a) % 8 + 8) % 8;
  return d > 4 ? d - 8 : d;
}

void SafetyChecker::fail(std::int64_t t, const std::string& what) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "t=%.3f ms: ", static_cast<double>(t) / static_cast<double>(kUnitsPerMs));
  violations_.push_back(buf + what);
}

void SafetyChecker::check(const Sample& s) {
  ++events_;
  // coils: a rest position, never two opposite coils (positions k and k + 2).
  const std::optional<int> pos = half_position(s.coils);
  const bool opposite = (s.coils & 0b0101U) == 0b0101U || (s.coils & 0b1010U) == 0b1010U;
  if (opposite) {
    fail(s.t, "coils " + bits(s.coils) + ": two opposite coils energised");
  } else if (!pos) {
    fail(s.t, "coils " + bits(s.coils) + ": not a rest position of the half-step table");
  }
  if (!started_) {
    started_ = true;
    coils_ = s.coils;
    running_ = s.running;
    motion_start_ = s.t;
    return;
  }
  if (s.running && !running_ && !s.step) {
    // A start: the first step's interval counts from here.
    motion_start_ = s.t;
    interval_ = 0;
    dir_ = 0;
  }
  const int delta = half_steps(coils_, s.coils);
  if (s.step) {
    ++steps_;
    if (!running_) {
      fail(s.t, "a step while the timer was stopped");
    } else {
      const std::int64_t interval = s.t - (interval_ == 0 ? motion_start_ : last_step_);
      const std::int64_t max_hz = s.half ? kMaxHzHalf : kMaxHzFull;
      const std::int64_t start_units = start_period_ticks(s.half) * kUnitsPerTick;
      // maxfreq: interval >= 1 / max_hz, exactly.
      if (interval * max_hz < kUnitsPerSecond) {
        fail(s.t, "a step at " + hz_of(interval) + ", above the maximum " + std::to_string(max_hz) + " Hz");
      }
      if (interval_ == 0) {
        // start: the first step of a motion at or below the start frequency.
        if (interval < start_units) fail(s.t, "a motion started at " + hz_of(interval) + ", above the start frequency");
      } else {
        // ramp: the period, counted as at most the start period, moves by at most 64 ticks.
        const std::int64_t a = std::min(interval_, start_units), b = std::min(interval, start_units);
        if (b - a > kAccelTicks * kUnitsPerTick || a - b > kAccelTicks * kUnitsPerTick) {
          fail(s.t, "the period went from " + ticks_of(interval_) + " to " + ticks_of(interval) +
                        " ticks above the start frequency (at most 64 per step)");
        }
      }
      // coils: one half step in half step, one full step (two half steps) in full step.
      const int want = s.half ? 1 : 2;
      if (delta != want && delta != -want) {
        fail(s.t, "a " + std::string(s.half ? "half" : "full") + " step went " + bits(coils_) + " -> " + bits(s.coils) +
                      " (" + std::to_string(delta) + " half steps)");
      } else {
        const int d = delta > 0 ? 1 : -1;
        // reverse: the step before the change and the step after it both at or below the
        // start frequency (docs/hc08.md "Ramp": down to it, reverse, and the first step the
        // other way is a start).
        if (dir_ != 0 && d != dir_ && (interval_ < start_units || interval < start_units)) {
          fail(s.t, "the direction reversed between steps at " + hz_of(interval_) + " and " + hz_of(interval) +
                        ", both above the start frequency");
        }
        dir_ = d;
      }
      interval_ = interval;
      last_step_ = s.t;
      // stop: the motion's last step at or below the start frequency.
      if (!s.running && interval < start_units) {
        fail(s.t, "the motor stopped after a step at " + hz_of(interval) + ", above the start frequency");
      }
    }
  } else if (s.coils != coils_) {
    if (running_ || s.running) {
      fail(s.t, "the coils changed between steps while running (" + bits(coils_) + " -> " + bits(s.coils) + ")");
    } else if (delta != 1) {
      fail(s.t, "the coils changed at rest by " + std::to_string(delta) + " half steps (" + bits(coils_) + " -> " +
                    bits(s.coils) + "; a drive change moves at most half a step forward)");
    }
  } else if (running_ && !s.running && interval_ != 0 && interval_ < start_period_ticks(s.half) * kUnitsPerTick) {
    // stopped without a step: the last step was the motion's last.
    fail(s.t, "the motor stopped after a step at " + hz_of(interval_) + ", above the start frequency");
  }
  coils_ = s.coils;
  running_ = s.running;
}

}  // namespace ap::sim::hc08
