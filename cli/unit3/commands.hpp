#pragma once
// The unit3 profile's command adapters that live in files of their own (cli/profile.hpp).
#include "profile.hpp"

namespace ap::cli {

// axisproof panel --profile unit3 (docs/panel.md "The unit3 panel").
int unit3_panel(const PanelArgs& a);

}  // namespace ap::cli
