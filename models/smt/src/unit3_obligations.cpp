// The 3-axis USB unit's obligations (docs/unit3.md). The joystick's are stated over the
// mapping as the core computes it: deflection() (core/unit3_joystick/joystick.hpp) is
// evaluated for each of the 1024 ADC codes and the results become a decision tree over a
// symbolic 10-bit code, so a change to the core's mapping is a change to what is proved.
#include <cstdint>
#include <string>

#include "core/unit3_joystick/joystick.hpp"
#include "models/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {
namespace {

namespace j = ap::unit3_joystick;
constexpr unsigned kAdcBits = 10;

// The core's value of `field` at every code in [lo, hi), as a term over `adc`.
template <class Field>
z3::expr graph(z3::context& c, const z3::expr& adc, unsigned lo, unsigned hi, Field field, unsigned bits) {
  if (hi - lo == 1) return c.bv_val(field(j::deflection(static_cast<std::uint16_t>(lo))), bits);
  const unsigned mid = lo + (hi - lo) / 2;
  return z3::ite(z3::ult(adc, c.bv_val(mid, kAdcBits)), graph(c, adc, lo, mid, field, bits),
                 graph(c, adc, mid, hi, field, bits));
}

struct Stick {
  z3::context& c;
  z3::expr adc;
  z3::expr index;  // 8 bits
  z3::expr dir;    // 2 bits: 0 stop, 1 up (+1), 3 down (-1)
  Stick(z3::context& ctx, const char* name)
      : c(ctx), adc(ctx.bv_const(name, kAdcBits)),
        index(graph(ctx, adc, 0, j::kAdcMax + 1U, [](j::Deflection d) { return unsigned{d.index}; }, 8)),
        dir(graph(ctx, adc, 0, j::kAdcMax + 1U, [](j::Deflection d) { return d.dir < 0 ? 3U : unsigned(d.dir); }, 2)) {}
  z3::expr code(unsigned v) const { return c.bv_val(v, kAdcBits); }
};

}  // namespace

ObligationList unit3_obligations() {
  ObligationList out;
  out.push_back({"unit3.joystick.index_in_table",
                 "QF_BV over all 1024 ADC codes of deflection() as the core computes it: a moving axis "
                 "indexes the 32-entry ramp table inside its bounds (eq. 6 alone gives 32 at ADC 0)",
                 [](unsigned ms) {
                   Stick s(shared_context(), "adc");
                   const z3::expr claim = z3::implies(s.dir != s.c.bv_val(0, 2), z3::ult(s.index, s.c.bv_val(j::kTableSize, 8)));
                   return check_valid(s.c, claim, ms, {{"adc", s.adc}, {"index", s.index}});
                 }});
  out.push_back({"unit3.joystick.dead_band",
                 "QF_BV over all 1024 ADC codes: the axis stops exactly for 500..524, moves down below and up above",
                 [](unsigned ms) {
                   Stick s(shared_context(), "adc");
                   const z3::expr in_band = z3::uge(s.adc, s.code(j::kDeadLow)) && z3::ule(s.adc, s.code(j::kDeadHigh));
                   const z3::expr claim = (s.dir == s.c.bv_val(0, 2)) == in_band &&
                                          z3::implies(z3::ult(s.adc, s.code(j::kDeadLow)), s.dir == s.c.bv_val(3, 2)) &&
                                          z3::implies(z3::ugt(s.adc, s.code(j::kDeadHigh)), s.dir == s.c.bv_val(1, 2));
                   return check_valid(s.c, claim, ms, {{"adc", s.adc}, {"dir", s.dir}});
                 }});
  out.push_back({"unit3.joystick.faster_farther",
                 "QF_BV over all pairs of ADC codes on one side of the dead band: the index never falls as the "
                 "stick moves away from the centre",
                 [](unsigned ms) {
                   Stick a(shared_context(), "a");
                   Stick b(shared_context(), "b");
                   const z3::expr below = z3::ult(a.adc, b.adc) && z3::ult(b.adc, a.code(j::kDeadLow));
                   const z3::expr above = z3::ugt(a.adc, a.code(j::kDeadHigh)) && z3::ult(a.adc, b.adc);
                   const z3::expr claim = z3::implies(below, z3::uge(a.index, b.index)) &&
                                          z3::implies(above, z3::ule(a.index, b.index));
                   return check_valid(a.c, claim, ms, {{"a", a.adc}, {"b", b.adc}, {"index_a", a.index}, {"index_b", b.index}});
                 }});
  return out;
}

}  // namespace ap::model::smt
