#pragma once
// The HC08 unit's message queue (seed 002 §5.2.2, docs/hc08.md "Queue"): interrupts push, the
// main loop pops in order; a fixed array, and "when the queue is full a new message is
// dropped" [T]. The motor sends one message per step (the angle, for the display); at 1700 Hz
// that alone would fill any queue and then drop the user's keys. So a motor message replaces
// one still waiting instead of queueing behind it (the display only needs the latest angle),
// and a key is dropped only when the queue is full of keys [D].
#include <array>
#include <cstdint>
#include <optional>

namespace ap::hc08_board {

enum class Source : std::uint8_t { Keyboard, Motor };  // KEYB, MOTOR [T]

struct Message {
  Source src = Source::Keyboard;
  std::uint16_t data = 0;  // a key code, or the rotor angle in tenths of a degree
};

class Queue {
 public:
  static constexpr std::uint8_t kCapacity = 8;  // [D]
  // False when the message was dropped (the queue full).
  bool push(const Message& m);
  std::optional<Message> pop();
  std::uint8_t size() const { return size_; }
  std::uint32_t dropped() const { return dropped_; }

 private:
  std::array<Message, kCapacity> buf_{};
  std::uint8_t head_ = 0;
  std::uint8_t size_ = 0;
  std::uint32_t dropped_ = 0;
};

}  // namespace ap::hc08_board
