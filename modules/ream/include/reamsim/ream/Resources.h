#pragma once
#include <string>

namespace reamsim {

// The folder holding the bundled resources (default bone, plan, reamer presets). Looked up in order:
// $REAMSIM_RESOURCE_DIR, <executable>/../share/reamsim/resources (installed), the source tree's
// resources/ (build tree). Throws std::runtime_error listing where it looked when none exists.
std::string resourceDir();
std::string resourcePath(const std::string& relative);

}  // namespace reamsim
