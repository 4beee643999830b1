// The BLE link's receive ring, shared by both peripheral layers (periph_qemu.cpp,
// periph_stm32l476.cpp). One producer, the receive interrupt, and one consumer, thread mode:
// each index is written by one side only, so no lock and no interrupt masking is needed on a
// single core. The indices count bytes since power-up and wrap at 2^32; with a power-of-two
// size the slot `index % N` stays continuous across that wrap.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ap::xy_fw {

template <std::uint32_t N>
class LinkRing {
  static_assert(N > 0 && (N & (N - 1)) == 0, "the slot index must survive the 2^32 wrap");

 public:
  // Interrupt side. False when the ring is full: the byte is dropped, and what that means
  // differs per image (the caller says).
  bool put(std::uint8_t b) {
    if (head_ - tail_ >= N) return false;
    buf_[head_ % N] = b;
    // The byte must be in its slot before the consumer can see the new head; volatile orders
    // only volatile accesses, and the slot is not one.
    __asm volatile("" ::: "memory");
    head_ = head_ + 1;
    return true;
  }

  // Thread side: moves at most `cap` bytes out; returns how many.
  std::size_t take(std::uint8_t* out, std::size_t cap) {
    std::size_t n = 0;
    while (n < cap && tail_ != head_) {
      out[n++] = buf_[tail_ % N];
      // The slot is read before the producer may reuse it.
      __asm volatile("" ::: "memory");
      tail_ = tail_ + 1;
    }
    return n;
  }

  // Bytes stored since power-up (wraps at 2^32).
  std::uint32_t received() const { return head_; }

 private:
  std::uint8_t buf_[N]{};
  volatile std::uint32_t head_ = 0;  // written only by the interrupt
  volatile std::uint32_t tail_ = 0;  // written only by thread mode
};

}  // namespace ap::xy_fw
