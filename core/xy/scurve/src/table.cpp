// The table S-curve is header-only (constexpr); this unit checks it builds at the thesis's N
// (the properties are tested in properties/xy/scurve) (docs/scurve.md "Table").
#include "core/xy/scurve/table.hpp"

namespace ap::xy_scurve {
static_assert(kThesisTable.sc.size() == kThesisEntries);
static_assert(kThesisTable.sc[kThesisEntries / 2 - 1] <= kOne / 2);
}  // namespace ap::xy_scurve
