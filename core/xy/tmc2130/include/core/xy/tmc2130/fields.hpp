#pragma once
// Typed field access on a register word. Values are range-checked against the datasheet
// range before any bit is touched: an out-of-range value is an error, never masked.
#include <cstdint>

#include "core/xy/tmc2130/bits.hpp"
#include "core/xy/tmc2130/regmap.hpp"
#include "core/xy/tmc2130/result.hpp"

namespace ap::xy_tmc2130 {

// A field assignment for batch writes. int64 holds every field range (32-bit MSLUT words and
// signed fields alike); the word image is the value modulo 2^32, which is injective on
// every field's [min, max].
struct FieldValue {
  Field field;
  std::int64_t value;
};

constexpr bool in_range(const FieldInfo& f, std::int64_t v) { return v >= f.min && v <= f.max; }

constexpr std::uint32_t sign_bit(const FieldInfo& f) {
  return std::uint32_t{1} << (f.width - 1u);
}

// The raw insert on a word the caller has already range-checked.
constexpr std::uint32_t insert_unchecked(std::uint32_t word, const FieldInfo& f, std::int64_t v) {
  return bits::insert<std::uint32_t>(word, f.mask, f.shift, static_cast<std::uint32_t>(v));
}

constexpr Result<std::uint32_t> field_set(std::uint32_t word, Field field, std::int64_t v) {
  const FieldInfo& f = info(field);
  if (!in_range(f, v)) return Error::ValueOutOfRange;
  return insert_unchecked(word, f, v);
}

constexpr std::int64_t field_get(std::uint32_t word, Field field) {
  const FieldInfo& f = info(field);
  const std::uint32_t raw = bits::extract<std::uint32_t>(word, f.mask, f.shift);
  if (!f.is_signed) return raw;
  return static_cast<std::int32_t>(bits::sign_extend<std::uint32_t>(raw, sign_bit(f)));
}

// Several fields of one register in one word: all are checked first, so a bad entry leaves
// `word` unchanged (the thesis's Obr. 7-12 problem of partial updates).
constexpr Result<std::uint32_t> fields_set(std::uint32_t word, Reg reg, const FieldValue* begin,
                                           const FieldValue* end) {
  for (const FieldValue* p = begin; p != end; ++p) {
    const FieldInfo& f = info(p->field);
    if (f.reg != reg) return Error::FieldNotInRegister;
    if (!in_range(f, p->value)) return Error::ValueOutOfRange;
    for (const FieldValue* q = begin; q != p; ++q) {
      if (q->field == p->field) return Error::DuplicateField;
    }
  }
  for (const FieldValue* p = begin; p != end; ++p) word = insert_unchecked(word, info(p->field), p->value);
  return word;
}

// Compile-time checked variants: a field of a read-only register does not compile.
template <Field F>
constexpr Result<std::uint32_t> field_set(std::uint32_t word, std::int64_t v) {
  static_assert(writable(info(F).reg), "field belongs to a read-only register");
  return field_set(word, F, v);
}

}  // namespace ap::xy_tmc2130
