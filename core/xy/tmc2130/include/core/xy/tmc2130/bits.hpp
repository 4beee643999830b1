#pragma once
// The masking arithmetic every field access goes through. It is a template over the word
// type so that models/smt instantiates this very code with Z3 bit-vectors and proves it for
// all 2^32 register values; the firmware instantiates it with std::uint32_t. Generic code
// here must only use & | ^ ~ - << >> on W and never build a W from a literal.
#include <cstdint>

namespace ap::xy_tmc2130::bits {

// FIELD_SET / FIELD_UPDATE of TMC-API: keep everything outside `mask`, put `value` inside.
// The trailing `& mask` is what stops a negative (sign-extended) value from spilling into
// the neighbouring fields.
template <class W>
constexpr W insert(W old, W mask, unsigned shift, W value) {
  return (old & ~mask) | ((value << shift) & mask);
}

template <class W>
constexpr W extract(W word, W mask, unsigned shift) {
  return (word & mask) >> shift;
}

// Two's-complement sign extension of a field whose top bit is `sign_bit`.
template <class W>
constexpr W sign_extend(W raw, W sign_bit) {
  return (raw ^ sign_bit) - sign_bit;
}

}  // namespace ap::xy_tmc2130::bits
