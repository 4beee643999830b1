// The stack paint (docs/qemu.md "Faults and the stack"): the reset handler fills the stack
// with a pattern; the words still holding it at the end of a run were never used.
#pragma once

#include <cstdint>

namespace ap::xy_fw {

inline constexpr std::uint32_t kStackPaint = 0xA5A5'5A5AU;

std::uint32_t stack_size();
// Bytes from the top of the stack down to the lowest word no longer holding the paint.
std::uint32_t stack_used();
// The lowest word of the thread stack was overwritten: it ran (at least) to its end.
bool stack_overflowed();
// The same for the exception stack (MSP), which sits above the thread stack: its overflow runs
// into the thread stack's top, so this check is the only one that sees it.
bool handler_stack_overflowed();

}  // namespace ap::xy_fw
