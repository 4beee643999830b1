#pragma once
// The HC08 unit's coil excitation (seed 002 §1.7, docs/hc08.md "Excitation"): the four phases
// of the SMR 300-100-RI/24 are driven straight from port A (phase 1..4 on PTA3..PTA6, a 1
// energises the coil [T Tab. 4.1]); full step ("four-step", 40 steps/rev, 9°) or half step
// ("eight-step", 80 steps/rev, 4.5°) [T Tab. 3.1]. The thesis stores "codes that correspond to
// the sequence of energised phases" and reverses by playing them backwards [T §5.3.3,
// 002_*.txt:1046]; the codes themselves were on its CD and are not in the text. So every table
// here is a reconstruction [D, docs/hc08.md "Excitation"]: the textbook sequences over the four
// coils in rotational order (two-phase or wave full step, half step alternating one and two
// coils), with the two open questions as parameters: whether full step energises one coil
// (wave) or two adjacent coils (two-phase, the default), and which phase sits at which
// rotational position (the default: phase 1, 2, 3, 4 in that order).
#include <array>
#include <cstdint>

namespace ap::hc08_drive {

enum class Drive : std::uint8_t { Full = 0, Half = 1 };  // four-step / eight-step [T]
enum class FullStep : std::uint8_t { TwoPhase = 0, Wave = 1 };

inline constexpr std::uint8_t kCoils = 4;
inline constexpr std::array<std::uint8_t, kCoils> kPhasePin = {3, 4, 5, 6};  // PTA bit of phase 1..4 [T]
constexpr std::uint16_t steps_per_rev(Drive d) { return d == Drive::Full ? 40 : 80; }  // [T Tab. 3.1]

// Coil patterns in rotational order: bit k is the coil at rotational position k.
struct Table {
  std::array<std::uint8_t, 8> pattern{};
  std::uint8_t length = 0;
};
inline constexpr Table kTwoPhase{{0b0011, 0b0110, 0b1100, 0b1001}, 4};
inline constexpr Table kWave{{0b0001, 0b0010, 0b0100, 0b1000}, 4};
inline constexpr Table kHalf{{0b0001, 0b0011, 0b0010, 0b0110, 0b0100, 0b1100, 0b1000, 0b1001}, 8};
constexpr const Table& table(Drive d, FullStep f) {
  return d == Drive::Half ? kHalf : (f == FullStep::Wave ? kWave : kTwoPhase);
}

// Which phase (0..3 = phase 1..4) sits at each rotational position; a permutation.
struct PhaseOrder {
  std::array<std::uint8_t, kCoils> phase{0, 1, 2, 3};
};
constexpr bool is_permutation(const PhaseOrder& o) {
  std::uint8_t seen = 0;
  for (const std::uint8_t p : o.phase) {
    if (p >= kCoils) return false;
    seen = static_cast<std::uint8_t>(seen | (1U << p));
  }
  return seen == 0x0F;
}

// The port A byte of a pattern: only PTA3..6 are the motor's; the other bits are 0.
constexpr std::uint8_t port_byte(std::uint8_t pattern, const PhaseOrder& o) {
  std::uint8_t b = 0;
  for (std::uint8_t k = 0; k < kCoils; ++k) {
    if ((pattern >> k) & 1U) b = static_cast<std::uint8_t>(b | (1U << kPhasePin[o.phase[k] & 3U]));
  }
  return b;
}

// The position in the table. Forward (+1) plays it in order, reverse (-1) backwards [T].
class Sequencer {
 public:
  constexpr Sequencer() = default;
  constexpr Sequencer(Drive d, FullStep f) : drive_(d), full_(f) {}
  constexpr void step(int dir) {
    const std::uint8_t n = table(drive_, full_).length;
    index_ = static_cast<std::uint8_t>(dir >= 0 ? (index_ + 1U) % n : (index_ + n - 1U) % n);
  }
  constexpr std::uint8_t pattern() const { return table(drive_, full_).pattern[index_]; }
  constexpr std::uint8_t index() const { return index_; }
  constexpr Drive drive() const { return drive_; }
  // A new drive type (at rest: the board changes it only then). The pattern on the coils is
  // kept where the new table has it (half step holds every full-step pattern); from a half-step
  // pattern full step lacks, the next one forward is taken: the rotor moves by at most half a
  // step (docs/hc08.md "Excitation"). Returns the half steps the rotor moves (0 or 1, forward).
  std::uint8_t set_drive(Drive d);

 private:
  Drive drive_ = Drive::Full;
  FullStep full_ = FullStep::TwoPhase;
  std::uint8_t index_ = 0;
};

}  // namespace ap::hc08_drive
