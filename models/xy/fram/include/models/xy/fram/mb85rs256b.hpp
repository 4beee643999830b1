#pragma once
// Behavioural model of the Fujitsu MB85RS256B (256 Kbit SPI FRAM), at the level the
// storage code can observe: opcodes, the write-enable latch, block protection, address
// roll-over, byte-granular writes; plus fault injection the real part only shows when it
// breaks (power cut after SPI byte k, stuck cells, transient bit flips on write or read).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/xy/storage/fram_device.hpp"

namespace ap::model {

class Mb85rs256b {
 public:
  static constexpr std::size_t kSize = 32768;
  static constexpr std::uint16_t kAddressMask = 0x7FFF;  // A15 is "don't care" on this part

  Mb85rs256b();

  // One CS-framed transaction (CS falls, bytes clocked, CS rises). Returns true: the model
  // never reports a bus error, a dead chip just answers 0xFF like an undriven, pulled-up MISO.
  bool transfer(std::span<const std::uint8_t> tx, std::span<std::uint8_t> rx);

  // Bus binding for the core's FramDevice / ParameterStore.
  xy_storage::SpiBus bus() noexcept;

  // Power: after `k` more SPI bytes are clocked in, the supply drops; the byte that was in
  // flight when the cut happened is lost, every completed byte stays. Nothing works until
  // power_on(), which clears the volatile latch as the real part does at power-up.
  void arm_power_cut_after(std::size_t k) noexcept;
  void power_on() noexcept;
  bool powered() const noexcept { return powered_; }
  // Total SPI bytes clocked in while powered (to measure a save and pick cut points).
  std::size_t bytes_clocked() const noexcept { return clocked_; }

  // Faults. A stuck cell ignores writes to the bits in `mask` and reads them as `value`.
  void stick_bits(std::uint16_t address, std::uint8_t mask, std::uint8_t value);
  // The next `count` writes (resp. reads) of `address` XOR the byte with `mask`.
  void flip_on_write(std::uint16_t address, std::uint8_t mask, std::uint32_t count);
  void flip_on_read(std::uint16_t address, std::uint8_t mask, std::uint32_t count);
  void clear_faults() noexcept;

  // Back door for tests and fuzzers: the array and the non-volatile status bits.
  std::span<std::uint8_t, kSize> memory() noexcept { return mem_; }
  std::span<const std::uint8_t, kSize> memory() const noexcept { return mem_; }
  std::uint8_t status() const noexcept;
  void set_wp_pin(bool high) noexcept { wp_high_ = high; }

 private:
  struct Flip {
    std::uint16_t address;
    std::uint8_t mask;
    std::uint32_t remaining;
    bool on_read;
  };
  struct Stuck {
    std::uint16_t address;
    std::uint8_t mask;
    std::uint8_t value;
  };

  bool clock_byte() noexcept;  // false when the power died before this byte
  bool protected_address(std::uint16_t address) const noexcept;
  std::uint8_t load(std::uint16_t address);
  void store(std::uint16_t address, std::uint8_t value);

  std::array<std::uint8_t, kSize> mem_{};
  bool wel_ = false;
  bool bp0_ = false;
  bool bp1_ = false;
  bool wpen_ = false;
  bool wp_high_ = true;
  bool powered_ = true;
  bool cut_armed_ = false;
  std::size_t cut_countdown_ = 0;
  std::size_t clocked_ = 0;
  std::vector<Flip> flips_;
  std::vector<Stuck> stuck_;
};

}  // namespace ap::model
