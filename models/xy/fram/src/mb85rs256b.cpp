#include "models/xy/fram/mb85rs256b.hpp"

#include <algorithm>

namespace ap::model {

namespace op = xy_storage::opcode;

Mb85rs256b::Mb85rs256b() {
  // Shipped parts read as zero; tests that need garbage write it through memory().
  mem_.fill(0x00);
}

xy_storage::SpiBus Mb85rs256b::bus() noexcept {
  return xy_storage::SpiBus{
      [](void* ctx, std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) noexcept {
        return static_cast<Mb85rs256b*>(ctx)->transfer(tx, rx);
      },
      this};
}

void Mb85rs256b::arm_power_cut_after(std::size_t k) noexcept {
  cut_armed_ = true;
  cut_countdown_ = k;
}

void Mb85rs256b::power_on() noexcept {
  powered_ = true;
  cut_armed_ = false;
  wel_ = false;
}

bool Mb85rs256b::clock_byte() noexcept {
  if (!powered_) return false;
  if (cut_armed_) {
    if (cut_countdown_ == 0) {
      powered_ = false;
      cut_armed_ = false;
      wel_ = false;
      return false;
    }
    --cut_countdown_;
  }
  ++clocked_;
  return true;
}

std::uint8_t Mb85rs256b::status() const noexcept {
  return static_cast<std::uint8_t>((wpen_ ? xy_storage::status::kWpen : 0U) | (bp1_ ? xy_storage::status::kBp1 : 0U) |
                                   (bp0_ ? xy_storage::status::kBp0 : 0U) | (wel_ ? xy_storage::status::kWel : 0U));
}

bool Mb85rs256b::protected_address(std::uint16_t address) const noexcept {
  // BP1:BP0 = 01 upper quarter, 10 upper half, 11 everything (datasheet block table).
  if (bp1_ && bp0_) return true;
  if (bp1_) return address >= 0x4000U;
  if (bp0_) return address >= 0x6000U;
  return false;
}

std::uint8_t Mb85rs256b::load(std::uint16_t address) {
  std::uint8_t v = mem_[address];
  for (const Stuck& s : stuck_) {
    if (s.address == address) v = static_cast<std::uint8_t>((v & ~s.mask) | (s.value & s.mask));
  }
  for (Flip& f : flips_) {
    if (f.on_read && f.address == address && f.remaining > 0) {
      v = static_cast<std::uint8_t>(v ^ f.mask);
      --f.remaining;
    }
  }
  return v;
}

void Mb85rs256b::store(std::uint16_t address, std::uint8_t value) {
  if (protected_address(address)) return;
  for (Flip& f : flips_) {
    if (!f.on_read && f.address == address && f.remaining > 0) {
      value = static_cast<std::uint8_t>(value ^ f.mask);
      --f.remaining;
    }
  }
  for (const Stuck& s : stuck_) {
    if (s.address == address) value = static_cast<std::uint8_t>((value & ~s.mask) | (s.value & s.mask));
  }
  mem_[address] = value;
}

bool Mb85rs256b::transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx) {
  std::fill(rx.begin(), rx.end(), std::uint8_t{0xFF});
  const std::size_t n = std::min(tx.size(), rx.size());
  std::size_t done = 0;  // bytes clocked in this transaction while powered
  std::uint8_t cmd = 0;
  std::uint16_t address = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!clock_byte()) return true;  // dead from here on: no CS-rise actions either
    done = i + 1;
    if (i == 0) {
      cmd = tx[0];
      if (cmd == op::kWren) wel_ = true;
      if (cmd == op::kWrdi) wel_ = false;
      continue;
    }
    switch (cmd) {
      case op::kRdsr: rx[i] = status(); break;
      case op::kWrsr:
        if (i == 1 && wel_ && !(wpen_ && !wp_high_)) {
          wpen_ = (tx[1] & xy_storage::status::kWpen) != 0;
          bp1_ = (tx[1] & xy_storage::status::kBp1) != 0;
          bp0_ = (tx[1] & xy_storage::status::kBp0) != 0;
        }
        break;
      case op::kRead:
      case op::kWrite:
        if (i == 1) {
          address = static_cast<std::uint16_t>(tx[1] << 8U);
        } else if (i == 2) {
          address = static_cast<std::uint16_t>((address | tx[2]) & kAddressMask);
        } else if (cmd == op::kRead) {
          rx[i] = load(address);
          address = static_cast<std::uint16_t>((address + 1U) & kAddressMask);
        } else {
          if (wel_) store(address, tx[i]);
          address = static_cast<std::uint16_t>((address + 1U) & kAddressMask);
        }
        break;
      default: break;  // unknown opcode: the part ignores the rest of the frame
    }
  }
  // CS rise: the latch resets after a WRITE or WRSR frame, as on the real part.
  if (done > 0 && (cmd == op::kWrite || cmd == op::kWrsr)) wel_ = false;
  return true;
}

void Mb85rs256b::stick_bits(std::uint16_t address, std::uint8_t mask, std::uint8_t value) {
  stuck_.push_back(Stuck{static_cast<std::uint16_t>(address & kAddressMask), mask, value});
}

void Mb85rs256b::flip_on_write(std::uint16_t address, std::uint8_t mask, std::uint32_t count) {
  flips_.push_back(Flip{static_cast<std::uint16_t>(address & kAddressMask), mask, count, false});
}

void Mb85rs256b::flip_on_read(std::uint16_t address, std::uint8_t mask, std::uint32_t count) {
  flips_.push_back(Flip{static_cast<std::uint16_t>(address & kAddressMask), mask, count, true});
}

void Mb85rs256b::clear_faults() noexcept {
  flips_.clear();
  stuck_.clear();
}

}  // namespace ap::model
