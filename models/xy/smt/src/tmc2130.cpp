#include "models/xy/smt/tmc2130.hpp"

#include "models/xy/smt/modules.hpp"

namespace ap::model::smt {

void add_tmc2130_obligations(ObligationList& out) {
  xy_tmc2130::add_obligations_using<xy_tmc2130::CodeKernel>(out, "tmc2130.");
}

}  // namespace ap::model::smt
