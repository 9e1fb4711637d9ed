#pragma once
// The half of the reaming loop that runs on the document's thread: applies a ReamComputation to the
// document in one batch (reamer pose, bone commit, log row, alerts).
#include <cstddef>
#include <optional>

#include "reamsim/core/AlertNode.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/LogNode.h"
#include "reamsim/core/ReamerNode.h"
#include "reamsim/ream/ReamEngine.h"

namespace reamsim {

struct CommitOptions {
  bool logEveryStep = true;  // false: only steps that removed bone get a log row (the GUI's cut log)
  // Set: cumulative = this − the bone's volume after the step, i.e. what is missing from the bone as it
  // now stands, so cuts the user undid are not counted (the GUI). Unset: running sum of the log.
  std::optional<double> initialVolumeMm3;
  std::string note;  // the step's log row is written with it (a plan pose's note)
};

// Precondition: bone.currentRevision() == computation.baseRevision (throws std::logic_error otherwise,
// e.g. the user undid while the step was computed: drop the computation instead). Moves `next` out of
// the computation. Returns the step's log entry (boneStateId = the committed revision, 0 if none).
CutLogEntry commitReamStep(Document& document, BoneNode& bone, ReamerNode& reamer, LogNode& log, AlertNode* alerts,
                           ReamComputation& computation, std::size_t stepIndex, const CommitOptions& options = {});

}  // namespace reamsim
