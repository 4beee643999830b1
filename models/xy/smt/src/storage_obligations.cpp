// FRAM map obligations from the same constexpr table the firmware uses
// (core/xy/storage/include/core/xy/storage/fram_map.hpp, kAbsoluteMap): over every 32-bit address,
// no address lies in two items, and every item lies inside the chip.
#include <string>

#include "core/xy/storage/fram_map.hpp"
#include "models/xy/smt/modules.hpp"
#include "models/smt/obligation.hpp"

namespace ap::model::smt {
namespace {

z3::expr in_region(z3::context& c, const z3::expr& x, const ap::xy_storage::Region& r) {
  // start <= x < start + length, in 64 bits so start + length cannot wrap.
  const z3::expr s = c.bv_val(static_cast<std::uint64_t>(r.start), 64);
  const z3::expr e = c.bv_val(static_cast<std::uint64_t>(r.start) + r.length, 64);
  const z3::expr xx = z3::zext(x, 32);
  return z3::uge(xx, s) && z3::ult(xx, e);
}

std::string region_name(const ap::xy_storage::Region& r) {
  return std::string(ap::xy_storage::entry(r.id).name) + (r.copy == 0 ? "@A" : "@B");
}

}  // namespace

void add_storage_obligations(ObligationList& out) {
  out.push_back({"storage.fram.disjoint",
                 "QF_BV exhaustive over all 2^32 addresses: no address in two items of kAbsoluteMap (both copies)",
                 [](unsigned ms) {
                   z3::context& c = shared_context();
                   const z3::expr x = c.bv_const("addr", 32);
                   const auto map = ap::xy_storage::address_map();
                   z3::expr ok = c.bool_val(true);
                   for (std::size_t i = 0; i < map.size(); ++i) {
                     for (std::size_t j = i + 1; j < map.size(); ++j) {
                       ok = ok && !(in_region(c, x, map[i]) && in_region(c, x, map[j]));
                     }
                   }
                   Shown show{{"addr", x}};
                   return check_valid(c, ok, ms, show);
                 }});
  out.push_back({"storage.fram.fits_chip",
                 "QF_BV exhaustive over all 2^32 addresses: every address of every item is < the chip size; no "
                 "empty item",
                 [](unsigned ms) {
                   z3::context& c = shared_context();
                   const z3::expr x = c.bv_const("addr", 32);
                   z3::expr ok = c.bool_val(true);
                   for (const auto& r : ap::xy_storage::address_map()) {
                     ok = ok && z3::implies(in_region(c, x, r), z3::ult(x, c.bv_val(ap::xy_storage::kChip.size_bytes, 32))) &&
                          c.bool_val(r.length > 0);
                   }
                   (void)region_name;
                   Shown show{{"addr", x}};
                   return check_valid(c, ok, ms, show);
                 }});
}

}  // namespace ap::model::smt
