#pragma once
// A long repair (minutes for a large dirty mesh) says where it is on a terminal: one line on stderr,
// rewritten in place ("repair: remesh: inside and outside near the surface  42 %"), cleared when done.
// Nothing when stderr is not a terminal, so that scripts and tests read the same output as before.
#include "reamsim/mesh/RepairProgress.h"

namespace reamsim::cli {

RepairProgress terminalProgress(const char* command);

}  // namespace reamsim::cli
