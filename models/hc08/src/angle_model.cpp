#include "models/hc08/angle_model.hpp"

namespace ap::model::hc08 {

int AngleModel::set_drive(bool half) {
  int moved = 0;
  // Full-step rest positions are the even half-step counts: the rotor starts on one at
  // power-up in four-step (docs/hc08.md "Power-up") and a full step is two half steps
  // (002_*.txt l. 462-463). An odd count is a position only half step has; going to full step
  // there takes the next pattern forward (docs/hc08.md "Excitation").
  if (!half && half_drive_ && floor_mod(half_, 2) != 0) {
    half_ += 1;
    moved = 1;
  }
  half_drive_ = half;
  // The commanded position is in degrees and stays (docs/hc08.md "Angle arithmetic"): the
  // drive type changes the size of a step, not the angle the user asked for (l. 724).
  return moved;
}

void AngleModel::turned(bool right, std::int64_t steps) {
  if (steps == 0) return;
  half_ += (right ? 1 : -1) * steps * half_steps_per_step(half_drive_);
  anchored_ = false;
}

std::int64_t AngleModel::plan_b(bool right, int angle_deg) {
  const std::int64_t here = half_ * kUnitsPerHalfStep;
  if (!anchored_) {
    commanded_ = here;  // a mode A run or a stopped move: count from where the rotor is
    anchored_ = true;
  }
  const std::int64_t s = right ? 1 : -1;
  commanded_ += s * angle_deg * kUnitsPerDegree;
  const std::int64_t unit = half_steps_per_step(half_drive_) * kUnitsPerHalfStep;
  // Whole steps towards the commanded position, rounded towards where the move starts (never
  // past it), and none against the move's direction (l. 724, 726): the carried remainder may lie
  // behind the rotor, after a move the other way or the forward half step of a drive change
  // ("Excitation"); the move then turns nothing.
  std::int64_t n = floor_div(s * (commanded_ - here), unit);
  if (n < 0) n = 0;
  planned_right_ = right;
  planned_ = n;
  planned_from_ = half_;
  return n;
}

void AngleModel::finish_b(std::int64_t done) {
  half_ = planned_from_ + (planned_right_ ? 1 : -1) * done * half_steps_per_step(half_drive_);
  if (done != planned_) anchored_ = false;  // stopped early: no debt (docs/hc08.md "Mode B")
  planned_ = 0;
}

CoilTracker::CoilTracker(std::uint8_t power_up_port) : index_(index_of(power_up_port)) { ok_ = index_ >= 0; }

int CoilTracker::index_of(std::uint8_t port) {
  // docs/hc08.md "Excitation": the half-step table's bytes for the default phase order; every
  // full-step pattern (two-phase or wave) is one of them.
  constexpr std::uint8_t kHalfTable[8] = {0x08, 0x18, 0x10, 0x30, 0x20, 0x60, 0x40, 0x48};
  for (int i = 0; i < 8; ++i) {
    if (kHalfTable[i] == port) return i;
  }
  return -1;
}

void CoilTracker::feed(std::uint8_t port) {
  const int i = index_of(port);
  if (i < 0 || !ok_) {
    ok_ = false;
    return;
  }
  const int d = static_cast<int>(floor_mod(i - index_, 8));
  static constexpr int kMove[8] = {0, 1, 2, 0, 0, 0, -2, -1};
  if (d >= 3 && d <= 5) ok_ = false;  // no single step or drive change moves the rotor that far
  half_ += kMove[d];
  index_ = i;
}

}  // namespace ap::model::hc08
