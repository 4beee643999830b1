// The 3-axis USB unit's obligations (docs/unit3.md). The counter's are stated in 64-bit
// two's complement over the core's own bounds (core/unit3/axis/counting.hpp). The joystick's are stated over the
// mapping as the core computes it: deflection() (core/unit3/joystick/joystick.hpp) is
// evaluated for each of the 1024 ADC codes and the results become a decision tree over a
// symbolic 10-bit code, so a change to the core's mapping is a change to what is proved.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/unit3/axis/counting.hpp"
#include "core/unit3/joystick/joystick.hpp"
#include "core/unit3/ramp/ramp.hpp"
#include "models/unit3/obligations.hpp"
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

namespace r = ap::unit3_ramp;
constexpr unsigned kEntryBits = 5;

// A per-entry table of the core (kTable) as a term over a symbolic 5-bit entry, 64 bits wide.
template <class Value>
z3::expr entry_graph(z3::context& c, const z3::expr& e, unsigned lo, unsigned hi, Value value) {
  if (hi - lo == 1) return c.bv_val(static_cast<std::uint64_t>(value(static_cast<std::uint8_t>(lo))), 64);
  const unsigned mid = lo + (hi - lo) / 2;
  return z3::ite(z3::ult(e, c.bv_val(mid, kEntryBits)), entry_graph(c, e, lo, mid, value), entry_graph(c, e, mid, hi, value));
}

// The most compare matches a timer at TOP can give in one ramp interval: ceil(clocks / period).
std::uint64_t most_pulses(std::uint8_t entry) {
  const std::uint64_t period = r::kTable.top[entry] + 1U;
  return (r::kIntervalClocks + period - 1) / period;
}

// next_entry(e, top entry, false, left) as the core computes it, as a term over a symbolic entry
// and a 64-bit remaining count. The core compares `left` only with the stop[] values, so the
// result is constant between consecutive ones: evaluating it at each of them (and past the
// last) for each entry gives the whole function.
z3::expr core_next_entry(z3::context& c, const z3::expr& e, const z3::expr& left) {
  std::vector<std::uint64_t> breaks;
  for (std::uint8_t i = 0; i < r::kEntries; ++i) breaks.push_back(r::kTable.stop[i]);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  const auto leaf = [&](std::uint8_t entry) {
    const auto at = [&](std::uint64_t rem) {
      return c.bv_val(static_cast<unsigned>(r::next_entry(entry, r::kEntries - 1, false, rem).entry), kEntryBits);
    };
    z3::expr t = at(~std::uint64_t{0});
    for (auto b = breaks.rbegin(); b != breaks.rend(); ++b) t = z3::ite(z3::ule(left, c.bv_val(*b, 64)), at(*b), t);
    return t;
  };
  z3::expr t = leaf(r::kEntries - 1);
  for (int i = r::kEntries - 2; i >= 0; --i) t = z3::ite(e == c.bv_val(static_cast<unsigned>(i), kEntryBits), leaf(static_cast<std::uint8_t>(i)), t);
  return t;
}

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
  out.push_back({"unit3.counter.no_overflow",
                 "QF_BV 64-bit: from any counter within +-(10^18 - 1), a move of any count up to the wire's "
                 "15 digits in either direction is computed without signed overflow, and plan_move's range check "
                 "keeps the counter within +-(10^18 - 1) (kMaxCounter, kMaxMoveCount of the core)",
                 [](unsigned ms) {
                   z3::context& c = shared_context();
                   namespace a = ap::unit3_axis;
                   const z3::expr counter = c.bv_const("counter", 64);
                   const z3::expr count = c.bv_const("count", 64);
                   const z3::expr down = c.bool_const("down");
                   const z3::expr max_c = c.bv_val(a::kMaxCounter, 64);
                   const z3::expr max_m = c.bv_val(static_cast<std::uint64_t>(a::kMaxMoveCount), 64);
                   const z3::expr pre = z3::sle(-max_c, counter) && z3::sle(counter, max_c) && z3::ule(count, max_m);
                   // plan_move: target = counter -/+ count, in int64.
                   const z3::expr target = z3::ite(down, counter - count, counter + count);
                   // The same sum in 66 bits cannot overflow: equal after sign extension means none did.
                   const z3::expr wide = z3::ite(down, z3::sext(counter, 2) - z3::zext(count, 2),
                                                 z3::sext(counter, 2) + z3::zext(count, 2));
                   const z3::expr no_wrap = z3::sext(target, 2) == wide;
                   const z3::expr accepted = z3::sle(-max_c, target) && z3::sle(target, max_c);
                   const z3::expr claim = z3::implies(pre, no_wrap && z3::implies(accepted, z3::sle(-max_c, target) && z3::sle(target, max_c)));
                   return check_valid(c, claim, ms, {{"counter", counter}, {"count", count}, {"down", down}});
                 }});
  out.push_back({"unit3.ramp.move_ends_at_start_speed",
                 "QF_BV 64-bit, by induction over ramp intervals, for every entry and every remaining count: with "
                 "stop[e] < remaining (true at entry 0 for any move), an interval at entry e > 0 cannot send the "
                 "last pulse, and the core's next_entry (tabulated exactly: it compares the count only with stop[]) "
                 "moves one entry at most and keeps stop[n] < remaining; so every PC move's last pulse is at entry 0",
                 [](unsigned ms) {
                   z3::context& c = shared_context();
                   const z3::expr e = c.bv_const("entry", kEntryBits);
                   const z3::expr rem = c.bv_const("remaining", 64);
                   const z3::expr k = c.bv_const("pulses_in_interval", 64);
                   const auto stop = [&](const z3::expr& x) { return entry_graph(c, x, 0, r::kEntries, [](std::uint8_t i) { return r::kTable.stop[i]; }); };
                   const z3::expr most = entry_graph(c, e, 0, r::kEntries, most_pulses);
                   const z3::expr zero = c.bv_val(0, kEntryBits);
                   const z3::expr one = c.bv_val(1, kEntryBits);
                   const z3::expr top = c.bv_val(r::kEntries - 1U, kEntryBits);
                   const z3::expr inv = z3::ult(stop(e), rem);
                   const z3::expr sent = z3::ule(k, most) && z3::ule(k, rem);
                   const z3::expr left = rem - k;
                   const z3::expr n = core_next_entry(c, e, left);
                   // The ramp's own rule besides: at most one entry up or down per interval.
                   const z3::expr one_step = z3::ule(n, z3::ite(z3::ult(e, top), e + one, e)) &&
                                             z3::uge(n, z3::ite(e == zero, zero, e - one));
                   const z3::expr base = z3::implies(z3::uge(rem, c.bv_val(1, 64)), z3::ult(stop(zero), rem));
                   const z3::expr not_last_above_zero = z3::implies(inv && sent && e != zero, z3::ult(k, rem));
                   const z3::expr step = z3::implies(inv && sent && z3::ult(k, rem), one_step && z3::ult(stop(n), left));
                   return check_valid(c, base && not_last_above_zero && step, ms,
                                      {{"entry", e}, {"remaining", rem}, {"pulses_in_interval", k}});
                 }});
  return out;
}

}  // namespace ap::model::smt
