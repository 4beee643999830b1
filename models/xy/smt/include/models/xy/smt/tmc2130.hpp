#pragma once
// TMC2130 field obligations. For every field of kFields (the table the driver uses) and
// with the driver's own bit kernels instantiated on Z3 bit-vectors:
//   isolation  inserting any in-range value into any of the 2^32 old words changes no bit
//              outside the field's mask;
//   readback   field_get(field_set(old, v)) == v, through the int64 -> uint32 conversion and
//              sign extension exactly as fields.hpp does it;
//   disjoint   after setting the field, setting any other field of the same register to any
//              in-range value leaves the first field reading back its value (no overlap).
// The kernel is a template parameter only so a test can plant a broken kernel and watch the
// obligations fail; production registration uses CodeKernel, i.e. core/xy/tmc2130/bits.hpp.
#include <string>

#include "core/xy/tmc2130/bits.hpp"
#include "core/xy/tmc2130/fields.hpp"
#include "core/xy/tmc2130/regmap.hpp"
#include "models/smt/bv.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt::xy_tmc2130 {

namespace chip = ap::xy_tmc2130;

struct CodeKernel {
  template <class W>
  static W insert(W old, W mask, unsigned shift, W value) {
    return chip::bits::insert<W>(old, mask, shift, value);
  }
  template <class W>
  static W extract(W word, W mask, unsigned shift) {
    return chip::bits::extract<W>(word, mask, shift);
  }
  template <class W>
  static W sign_extend(W raw, W sign_bit) {
    return chip::bits::sign_extend<W>(raw, sign_bit);
  }
};

// A field's symbolic value: 64 bits like the API's std::int64_t, constrained to [min, max].
struct SymValue {
  z3::expr v64;
  z3::expr in_range;
  Bv word;  // static_cast<std::uint32_t>(v64): the low 32 bits
};

inline SymValue sym_value(z3::context& c, const chip::FieldInfo& f, const std::string& name) {
  z3::expr v = c.bv_const(name.c_str(), 64);
  z3::expr lo = c.bv_val(static_cast<std::int64_t>(f.min), 64);
  z3::expr hi = c.bv_val(static_cast<std::int64_t>(f.max), 64);
  // min/max are int64 and the API compares as int64: signed 64-bit comparison.
  return {v, v >= lo && v <= hi, Bv{v.extract(31, 0)}};
}

template <class K>
Bv sym_insert(z3::context& c, const Bv& old, const chip::FieldInfo& f, const SymValue& v) {
  return K::template insert<Bv>(old, bv(c, f.mask), f.shift, v.word);
}

// field_get(): extract, sign-extend signed fields, widen to int64.
template <class K>
z3::expr sym_get(z3::context& c, const Bv& word, const chip::FieldInfo& f) {
  const Bv raw = K::template extract<Bv>(word, bv(c, f.mask), f.shift);
  if (!f.is_signed) return z3::zext(raw.e, 32);
  const Bv ext = K::template sign_extend<Bv>(raw, bv(c, chip::sign_bit(f)));
  return z3::sext(ext.e, 32);
}

inline std::string field_path(const chip::FieldInfo& f) {
  return std::string(chip::info(f.reg).name) + "." + std::string(f.name);
}

template <class K>
void add_obligations_using(ObligationList& out, const std::string& prefix) {
  const std::string values = "all 2^32 old words x all in-range values";
  for (const auto& field : chip::kFields) {
    const chip::FieldInfo* f = &field;
    const std::string base = prefix + field_path(field);
    out.push_back({base + ".isolation", "SMT QF_BV: " + values, [f](unsigned timeout_ms) {
                     z3::context& c = shared_context();
                     const Bv old{c.bv_const("old", 32)};
                     const SymValue v = sym_value(c, *f, "v");
                     const Bv next = sym_insert<K>(c, old, *f, v);
                     const z3::expr outside = ~bv(c, f->mask).e;
                     const z3::expr claim = z3::implies(v.in_range, ((next.e ^ old.e) & outside) == 0);
                     return check_valid(c, claim, timeout_ms,
                                        {{"old", old.e}, {"v", v.v64}, {"new", next.e}});
                   }});
    out.push_back({base + ".readback", "SMT QF_BV: " + values, [f](unsigned timeout_ms) {
                     z3::context& c = shared_context();
                     const Bv old{c.bv_const("old", 32)};
                     const SymValue v = sym_value(c, *f, "v");
                     const Bv next = sym_insert<K>(c, old, *f, v);
                     const z3::expr back = sym_get<K>(c, next, *f);
                     const z3::expr claim = z3::implies(v.in_range, back == v.v64);
                     return check_valid(c, claim, timeout_ms,
                                        {{"old", old.e}, {"v", v.v64}, {"new", next.e}, {"read", back}});
                   }});
    out.push_back({base + ".disjoint", "SMT QF_BV: " + values + ", every other field of the register",
                   [f](unsigned timeout_ms) {
                     z3::context& c = shared_context();
                     const Bv old{c.bv_const("old", 32)};
                     const SymValue v = sym_value(c, *f, "v");
                     Bv word = sym_insert<K>(c, old, *f, v);
                     z3::expr assumptions = v.in_range;
                     Shown show{{"old", old.e}, {"v", v.v64}};
                     const auto& r = chip::info(f->reg);
                     for (std::size_t i = r.first_field; i < std::size_t{r.first_field} + r.field_count; ++i) {
                       const auto& g = chip::kFields[i];
                       if (&g == f) continue;
                       const SymValue w = sym_value(c, g, std::string(g.name));
                       word = sym_insert<K>(c, word, g, w);
                       assumptions = assumptions && w.in_range;
                       show.emplace_back(std::string(g.name), w.v64);
                     }
                     const z3::expr back = sym_get<K>(c, word, *f);
                     show.emplace_back("read", back);
                     return check_valid(c, z3::implies(assumptions, back == v.v64), timeout_ms, show);
                   }});
  }
}

}  // namespace ap::model::smt::xy_tmc2130
