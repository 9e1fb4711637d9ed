#pragma once
// The local exact CSG engine (modules/csg LocalSubtractor) as a cut backend of the reaming loop.
#include "reamsim/ream/ReamBackends.h"

namespace reamsim {

// Unlike the reference, accepts open and dirty bones; a cut that reaches a defect throws CutError
// (a std::runtime_error) and leaves the bone unchanged. bandCleanup: the engine's clean-up of the cut band
// after each cut (docs/CSG.md); off, the bone is the exact Boolean alone and its faces grow.
CutBackendFactory localCutBackendFactory(bool bandCleanup = true);

}  // namespace reamsim
