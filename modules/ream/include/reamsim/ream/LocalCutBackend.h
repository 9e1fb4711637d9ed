#pragma once
// The local exact CSG engine (modules/csg LocalSubtractor) as a cut backend of the reaming loop.
#include "reamsim/ream/ReamBackends.h"

namespace reamsim {

// Unlike the reference, accepts open and dirty bones; a cut that reaches a defect throws CutError
// (a std::runtime_error) and leaves the bone unchanged.
CutBackendFactory localCutBackendFactory();

}  // namespace reamsim
