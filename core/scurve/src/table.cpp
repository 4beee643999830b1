// The table S-curve is header-only (constexpr); this unit checks it builds at the thesis's N
// (the properties are tested in properties/scurve) (docs/scurve.md "Table").
#include "core/scurve/table.hpp"

namespace ap::scurve {
static_assert(kThesisTable.sc.size() == kThesisEntries);
static_assert(kThesisTable.sc[kThesisEntries / 2 - 1] <= kOne / 2);
}  // namespace ap::scurve
