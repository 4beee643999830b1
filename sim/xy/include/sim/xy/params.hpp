// Parameter names used by scenarios (param.NAME, fram.NAME, "board param NAME V") and their
// FRAM map items: the short names of docs/scenarios.md plus every map name of docs/storage.md.
#pragma once

#include <optional>
#include <string_view>

#include "core/xy/storage/fram_map.hpp"

namespace ap::sim::xy {

std::optional<xy_storage::ParamId> param_by_name(std::string_view name);

}  // namespace ap::sim::xy
