#pragma once
// One row of the cut log: what happened at one simulation step.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "reamsim/core/Pose.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

struct CutLogEntry {
  std::size_t stepIndex = 0;
  std::int64_t timeUnixMs = 0;    // wall-clock time the step was committed (ms since 1970-01-01 UTC)
  Pose pose;
  bool boxesOverlap = false;
  bool contact = false;
  double minDistanceMm = 0;       // reamer-bone distance before the cut (0 at contact)
  double removedMm3 = 0;          // bone removed by this step
  double cumulativeMm3 = 0;       // bone removed since the start of the session
  double cutMs = 0;               // wall time of the Boolean
  std::size_t faces = 0;          // live triangles of the bone after the step
  std::optional<Vec3> contactPoint;  // set when contact
  // A step that moved the reamer onto the bone: where along the move (0..1) and where on the bone its
  // cutting solid first met the bone (the exact first-contact query; unset without a move or a meeting).
  std::optional<double> moveContactT;
  std::optional<Vec3> moveContactPoint;
  std::uint64_t boneStateId = 0;  // BoneHistory revision committed by this step (0: none)
  // The reamer that made the step (a session may change reamers): its name, chord diameter and cap sphere
  // radius (unset for a flat reamer).
  std::string reamer;
  double reamerDiameterMm = 0;
  std::optional<double> reamerSphereRadiusMm;
  // Free text an educator or surgeon attached to the step (the log dock's note column, a plan pose's "note").
  std::string note;
  // The step's cut was not in the bone when its log was written (undone: the log keeps the row, it records what
  // was done). Written by a save and a crash copy, read back with the log; a row of the running session is
  // judged by the bone's history instead (boneStateId).
  bool undone = false;
};

}  // namespace reamsim
