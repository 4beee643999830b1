#pragma once
// A 32-bit Z3 bit-vector that behaves like std::uint32_t under the operators a core's generic
// bit kernels use (its templates over the word type, docs/proofs.md), so those kernels can be
// instantiated symbolically: the proof is about the code, not about a transcription of it.
#include <cstdint>

#include <z3++.h>

namespace ap::model::smt {

struct Bv {
  z3::expr e;
};

inline Bv bv(z3::context& c, std::uint32_t v) { return {c.bv_val(static_cast<unsigned>(v), 32)}; }
inline Bv operator&(const Bv& a, const Bv& b) { return {a.e & b.e}; }
inline Bv operator|(const Bv& a, const Bv& b) { return {a.e | b.e}; }
inline Bv operator^(const Bv& a, const Bv& b) { return {a.e ^ b.e}; }
inline Bv operator-(const Bv& a, const Bv& b) { return {a.e - b.e}; }
inline Bv operator~(const Bv& a) { return {~a.e}; }
// uint32 << s and >> s are only defined for s < 32; bvshl/bvlshr agree with C++ there.
inline Bv operator<<(const Bv& a, unsigned s) { return {z3::shl(a.e, a.e.ctx().bv_val(s, 32))}; }
inline Bv operator>>(const Bv& a, unsigned s) { return {z3::lshr(a.e, a.e.ctx().bv_val(s, 32))}; }

}  // namespace ap::model::smt
