#include "core/hc08/drive/drive.hpp"

namespace ap::hc08_drive {

// The port bytes of the default order, as seed-002.md §1.7 reconstructs them (two-phase 0x18
// 0x30 0x60 0x48). Not the thesis's: it gives only the pin of each phase (PTA3..6, Tab. 4.1,
// 002_*.txt:676-688) and that its codes are stored and played backwards to reverse
// (002_*.txt:1046); the codes themselves were on its CD. The tables and the phase order behind
// these bytes are docs/hc08.md's decisions ("Excitation").
static_assert(port_byte(kTwoPhase.pattern[0], PhaseOrder{}) == 0x18);
static_assert(port_byte(kTwoPhase.pattern[3], PhaseOrder{}) == 0x48);
static_assert(port_byte(kHalf.pattern[5], PhaseOrder{}) == 0x60);

std::uint8_t Sequencer::set_drive(Drive d) {
  if (d == drive_) return 0;
  const std::uint8_t now = pattern();
  drive_ = d;
  const Table& t = table(drive_, full_);
  for (std::uint8_t i = 0; i < t.length; ++i) {
    if (t.pattern[i] == now) {
      index_ = i;
      return 0;
    }
  }
  // Half to full from a pattern full step lacks: the next forward pattern of the old table.
  const Table& half = kHalf;
  std::uint8_t at = 0;
  for (std::uint8_t i = 0; i < half.length; ++i) {
    if (half.pattern[i] == now) at = i;
  }
  const std::uint8_t next = half.pattern[(at + 1U) % half.length];
  for (std::uint8_t i = 0; i < t.length; ++i) {
    if (t.pattern[i] == next) index_ = i;
  }
  return 1;
}

}  // namespace ap::hc08_drive
