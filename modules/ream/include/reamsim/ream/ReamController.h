#pragma once
// The reaming loop on the shared document: a new reamer pose → collision query → if the cutting volume
// reaches the bone, subtract it → commit a new bone state and a log row → alerts. The CLI and the tests
// drive cutting through this class; the GUI runs its two halves (ReamEngine, commitReamStep) itself.
//
// Collision: the BVH engine by default (exact overlap, distance and depth; the Boolean runs only when the
// cutting volume reaches the bone) or the thesis's rays (the Boolean runs whenever the boxes overlap).
#include <memory>
#include <optional>

#include "reamsim/ream/ReamEngine.h"
#include "reamsim/ream/ReamStep.h"

namespace reamsim {

struct ReamStepOutcome {
  CutLogEntry entry;
  ContactResult contact;
  ReferenceCut cut;
  double volumeBookkeepingError = 0;  // |removed − (V_before − V_after)|
  bool swept = false;                 // the step cut the volume swept from the previous pose
  int sweepCuts = 0;                  // swept: Booleans it took (ReamComputation::sweepCuts)
  ReamComputation::Times times;       // the engine's half (ReamEngine::compute)
  double commitMs = 0;                // the document's half (commitReamStep)
};

// Synchronous composition of the two halves (ReamEngine off-thread part, commitReamStep document
// part) with the reference backends; the GUI runs the same halves with the engine on a worker.
class ReamController {
 public:
  // The reamer node must have its cutting volume set (reamer-local coordinates).
  // `cut` picks the cutting engine (issue 4: referenceCutBackendFactory() or localCutBackendFactory()).
  ReamController(Document& document, BoneNode& bone, ReamerNode& reamer, LogNode& log, AlertNode* alerts = nullptr,
                 CutBackendFactory cut = referenceCutBackendFactory(),
                 std::unique_ptr<ContactBackend> contact = makeBvhContactBackend());
  ~ReamController();

  // A step to `pose`: a move from the previous step's pose (what it sweeps is cut), or with `placed` a
  // placement (nothing swept to it, as the first step always is). `note` goes on the step's log row.
  ReamStepOutcome moveTo(const Pose& pose, bool placed = false, const std::string& note = {});

  // Invariants of the current bone as the engine holds it (exact and rounded coordinates); costly.
  BoneInvariants checkBone() const;

 private:
  Document& document_;
  BoneNode& bone_;
  ReamerNode& reamer_;
  LogNode& log_;
  AlertNode* alerts_;
  ReamEngine engine_;
  std::size_t steps_ = 0;
  std::optional<Pose> previous_;  // the pose of the last step (the path's previous point)
};

}  // namespace reamsim
