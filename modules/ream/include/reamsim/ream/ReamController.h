#pragma once
// The reaming loop on the shared document: a new reamer pose → collision query → if the cutting volume
// reaches the bone, subtract it → commit a new bone state and a log row → alerts. The CLI, the tests
// and (later) the GUI all drive cutting through this class.
//
// This is the Foundation's correct path: thesis collision (bounding boxes, then Möller–Trumbore rays
// from the cutting-face vertices along the axis) and CGAL whole-mesh corefinement with exact
// constructions. Whenever the boxes overlap the exact Boolean runs, so a contact the rays cannot see
// (bone entering from the side) is still cut; the rays give the axial gap and the contact point.
#include <memory>

#include "reamsim/collision/ThesisContact.h"
#include "reamsim/core/AlertNode.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/LogNode.h"
#include "reamsim/core/ReamerNode.h"
#include "reamsim/csg/ReferenceSubtractor.h"

namespace reamsim {

struct ReamStepOutcome {
  CutLogEntry entry;
  ThesisContactResult contact;
  ReferenceCut cut;
  double volumeBookkeepingError = 0;  // |removed − (V_before − V_after)|
};

class ReamController {
 public:
  // The reamer node must have its cutting volume set (reamer-local coordinates).
  ReamController(Document& document, BoneNode& bone, ReamerNode& reamer, LogNode& log, AlertNode* alerts = nullptr);
  ~ReamController();

  ReamStepOutcome moveTo(const Pose& pose);

  // Invariants of the current bone as the engine holds it (exact and rounded coordinates); costly.
  BoneInvariants checkBone() const;

 private:
  void syncEngineWithBone();

  Document& document_;
  BoneNode& bone_;
  ReamerNode& reamer_;
  LogNode& log_;
  AlertNode* alerts_;
  std::unique_ptr<ReferenceSubtractor> engine_;
  std::uint64_t engineRevision_ = 0;
  std::vector<Vec3> localFaceVertices_;
  std::size_t steps_ = 0;
};

// Vertices of a cutting volume that face the feed direction (+Z): the probes of the thesis's rays.
std::vector<Vec3> forwardFacingVertices(const TriangleMesh& cuttingVolume);

}  // namespace reamsim
