#include "core/hc08/board/queue.hpp"

namespace ap::hc08_board {

bool Queue::push(const Message& m) {
  if (m.src == Source::Motor) {
    for (std::uint8_t i = 0; i < size_; ++i) {
      Message& waiting = buf_[(head_ + i) % kCapacity];
      if (waiting.src == Source::Motor) {
        waiting.data = m.data;
        return true;
      }
    }
  }
  if (size_ == kCapacity) {
    ++dropped_;
    return false;
  }
  buf_[(head_ + size_) % kCapacity] = m;
  ++size_;
  return true;
}

std::optional<Message> Queue::pop() {
  if (size_ == 0) return std::nullopt;
  const Message m = buf_[head_];
  head_ = static_cast<std::uint8_t>((head_ + 1U) % kCapacity);
  --size_;
  return m;
}

}  // namespace ap::hc08_board
