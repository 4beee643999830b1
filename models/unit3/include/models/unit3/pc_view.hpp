#pragma once
// What the PC should see of the 3-axis USB unit (docs/unit3.md): its replies to every byte,
// button and endstop, given the STEP/DIR pins it watches. Written from docs/unit3.md and seed
// 001 alone (its own line reader, menu and counting), so a test that runs it beside the
// firmware compares two readings of the same text. Timing is not modelled: the pins say when
// a pulse went out; the model says what every pulse and reply must be.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ap::model::unit3 {

struct Pins {
  std::array<int, 3> pulses{};  // STEP pulses of the tick, per axis
  std::array<int, 3> dir{};     // DIR, +1 / -1
  std::array<bool, 3> running{};  // an axis in motion (the stick's motion is timing the model leaves to the unit)
};

class PcView {
 public:
  struct Settings {
    std::array<int, 3> mode{0, 0, 0};    // a blank EEPROM: full step and M6 (docs/unit3.md "Settings")
    std::array<int, 3> thread{4, 4, 4};
  };

  // Bytes from the PC; returns the replies the unit owes for them, in order.
  std::vector<std::string> receive(const std::string& bytes, std::uint8_t endstops);
  // A button; returns the replies.
  std::vector<std::string> press(int button);  // 0 Enter, 1 Back, 2 Up, 3 Down, 4 Left, 5 Right
  // One tick's pins. Returns false with `why` when a pulse is one the model forbids (towards a
  // closed endstop, against a PC move's direction, past its count) or an axis without a PC move
  // starts outside the POSITIONS window (the stick drives there only). `stopped` gets the axes
  // whose PC move ended in this tick (a report of each is owed), `cut` those an endstop cut (E23).
  bool tick(const Pins& p, std::uint8_t endstops, std::vector<int>& stopped, std::vector<int>& cut, std::string& why);
  // Power cycle: counters 0, the stored settings back (the model stores on every save).
  void power_cycle();

  std::int64_t counter(int a) const { return axes_[static_cast<std::size_t>(a)].counter; }
  const Settings& settings() const { return settings_; }
  static std::string report(int axis, std::int64_t count);

 private:
  struct Axis {
    std::int64_t counter = 0;
    std::uint64_t remaining = 0;
    int move_dir = 1;
    int mode = 0;          // on the MODE pins
    bool running = false;  // as the last tick's pins showed
  };
  std::vector<std::string> line(const std::string& l, std::uint8_t endstops);
  static std::vector<std::string> settings_replies(const Settings& s);
  std::vector<std::string> zero();

  Settings settings_{};
  Settings stored_{};
  std::array<Axis, 3> axes_{};
  std::array<int, 3> latched_{1, 1, 1};
  std::string pending_;
  bool dropping_ = false;
  int window_ = 0;  // 0 positions, 1 menu, 2 step size, 3 thread
  int item_ = 0;
  int sel_ = 0;
};

}  // namespace ap::model::unit3
