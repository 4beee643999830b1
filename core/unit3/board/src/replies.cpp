#include "core/unit3/board/replies.hpp"

namespace ap::unit3_board {

bool Replies::put(std::span<const std::uint8_t> bytes) {
  if (bytes.size() > kCapacity - size_) {
    ++dropped_;
    return false;
  }
  for (const std::uint8_t b : bytes) {
    buf_[(head_ + size_) % kCapacity] = b;
    ++size_;
  }
  return true;
}

std::size_t Replies::take(std::span<std::uint8_t> out) {
  std::size_t n = 0;
  while (n < out.size() && size_ > 0) {
    out[n++] = buf_[head_];
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  return n;
}

}  // namespace ap::unit3_board
