// The image's application (src/main.cpp), entered by the reset handler once the C++ run-time
// is set up; returns when the host ends a co-simulated run (the board never does).
#pragma once

namespace ap::xy_fw {

void run();

}  // namespace ap::xy_fw
