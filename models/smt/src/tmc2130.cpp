#include "models/smt/tmc2130.hpp"

#include "models/smt/modules.hpp"

namespace ap::model::smt {

void add_tmc2130_obligations(ObligationList& out) {
  tmc2130::add_obligations_using<tmc2130::CodeKernel>(out, "tmc2130.");
}

}  // namespace ap::model::smt
