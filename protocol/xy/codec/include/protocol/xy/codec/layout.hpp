#pragma once
// Byte layout of the command and echo frames (docs/protocol.md has the byte-by-byte table).
// Every frame has a fixed length so that the MCU's fixed-count UART receive and the stream
// framer agree on where a frame ends; the start characters never occur inside a frame, so a
// receiver that lost a byte finds the next frame by hunting for one.
#include <cstddef>
#include <cstdint>

namespace ap::xy_codec {

inline constexpr char kCommandStart = '>';  // PC -> board
inline constexpr char kEchoStart = '<';     // board -> PC
inline constexpr char kEnd = ';';

inline constexpr std::size_t kStartWidth = 1;
inline constexpr std::size_t kSeqWidth = 3;     // decimal, 000..999, wraps
inline constexpr std::size_t kIdWidth = 2;      // decimal, 00..99
inline constexpr std::size_t kDataWidth = 6;    // see kDataMin/kDataMax
inline constexpr std::size_t kSubIdWidth = 2;   // decimal
inline constexpr std::size_t kSubArgWidth = 2;  // decimal
inline constexpr std::size_t kCrcWidth = 4;     // upper-case hex of CRC-16/CCITT-FALSE
inline constexpr std::size_t kEndWidth = 1;
inline constexpr std::size_t kSubscriberSlots = 4;

inline constexpr std::uint16_t kSeqModulo = 1000;

// Delivery (docs/protocol.md "Delivery"): a frame whose seq is 1..499 ahead of the last one the
// board executed (mod 1000) is new, 0 ahead is a repeat of that frame, 500..999 ahead is older.
// Half the seq space each way, so a seq cannot be new and older at once; the client keeps one
// frame in flight, so the two ends are never more than a few seqs apart.
inline constexpr std::uint16_t kSeqNewWindow = kSeqModulo / 2 - 1;  // 499

enum class SeqOrder : std::uint8_t { New, Repeat, Older };

// Where seq `s` stands relative to `last` (both 0..999; larger values are reduced mod 1000).
constexpr SeqOrder seq_order(std::uint16_t last, std::uint16_t s) {
  const unsigned ahead = (static_cast<unsigned>(s % kSeqModulo) + kSeqModulo - last % kSeqModulo) % kSeqModulo;
  if (ahead == 0) return SeqOrder::Repeat;
  return ahead <= kSeqNewWindow ? SeqOrder::New : SeqOrder::Older;
}

constexpr std::uint16_t seq_next(std::uint16_t s) { return static_cast<std::uint16_t>((s + 1U) % kSeqModulo); }

// Data fields: six characters, either six digits (0..999999) or '-' and five digits
// (-99999..-1). "-00000" is not canonical and is rejected, so every value has exactly one
// spelling and format(parse(b)) == b holds.
inline constexpr std::int32_t kDataMin = -99999;
inline constexpr std::int32_t kDataMax = 999999;

inline constexpr std::size_t kSlotWidth = kSubIdWidth + kSubArgWidth;
inline constexpr std::size_t kPacketWidth = kSlotWidth + kDataWidth;

// Offsets common to both frame kinds.
inline constexpr std::size_t kSeqOffset = kStartWidth;
inline constexpr std::size_t kXIdOffset = kSeqOffset + kSeqWidth;
inline constexpr std::size_t kXDataOffset = kXIdOffset + kIdWidth;
inline constexpr std::size_t kYIdOffset = kXDataOffset + kDataWidth;
inline constexpr std::size_t kYDataOffset = kYIdOffset + kIdWidth;
inline constexpr std::size_t kSubsOffset = kYDataOffset + kDataWidth;

// Command: slots are (subscriber ID, argument).
inline constexpr std::size_t kCommandCrcOffset = kSubsOffset + kSubscriberSlots * kSlotWidth;
inline constexpr std::size_t kCommandEndOffset = kCommandCrcOffset + kCrcWidth;
inline constexpr std::size_t kCommandLength = kCommandEndOffset + kEndWidth;

// Echo: packets are (subscriber ID, argument, data), the slot copied from the command.
inline constexpr std::size_t kEchoCrcOffset = kSubsOffset + kSubscriberSlots * kPacketWidth;
inline constexpr std::size_t kEchoEndOffset = kEchoCrcOffset + kCrcWidth;
inline constexpr std::size_t kEchoLength = kEchoEndOffset + kEndWidth;

inline constexpr std::size_t kMaxFrameLength = kEchoLength > kCommandLength ? kEchoLength : kCommandLength;

static_assert(kCommandLength == 41, "docs/protocol.md documents a 41-byte command");
static_assert(kEchoLength == 65, "docs/protocol.md documents a 65-byte echo");

}  // namespace ap::xy_codec
