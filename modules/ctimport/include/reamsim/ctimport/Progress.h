#pragma once
// Progress reporting and cancellation for long operations. The callback receives the overall fraction
// (0..1) and the current stage's name; returning false cancels: the operation stops at the next check
// and throws ImportCancelled. It may be called from the calling thread only. (The same callback type and
// cancel base as the repair's: reamsim/mesh/RepairProgress.h.)
#include <string>

#include "reamsim/mesh/RepairProgress.h"

namespace reamsim::ct {

using ProgressCallback = reamsim::ProgressCallback;

class ImportCancelled : public StageCancelled {
 public:
  explicit ImportCancelled(const std::string& stage) : StageCancelled("cancelled during " + stage, stage) {}
};

}  // namespace reamsim::ct
