#pragma once
// A reaming report for review (clinicians, educators): one self-contained HTML file with the bone, the
// reamer, the scapular landmarks and the reamer axis's version and inclination, the removed volume, one row
// per cut, and optionally a picture of the view. Written by the window (File → Export a report…) and by
// `reamsim-cli ream` (DIR/report.html). docs/FORMATS.md "Reaming report".
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "reamsim/core/CutLogEntry.h"
#include "reamsim/core/PatientFrame.h"
#include "reamsim/core/Pose.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/core/ScapulaLandmarks.h"
#include "reamsim/ream/GlenoidFace.h"
#include "reamsim/tools/ReamedSurface.h"

namespace reamsim {

// The glenoid face of one bone state (reamsim/ream/GlenoidFace.h), or why there is none.
struct ReportedGlenoidFace {
  std::optional<GlenoidFace> face;
  std::string problem;  // empty with no face: not measured
};

struct ReamReportInput {
  std::string title = "ReamSim reaming report";
  std::string boneName, boneSource;
  PatientFrame patientFrame = PatientFrame::Unspecified;
  double volumeAtStartMm3 = 0;  // the bone as opened (the log's cumulative volume is measured from it)
  double volumeNowMm3 = 0;
  std::size_t facesAtStart = 0, facesNow = 0;
  ReamerSpec reamer;                // the reamer now
  std::optional<Pose> reamerPose;   // where it is now
  ScapulaLandmarks landmarks;       // the bone's (any not placed: no frame, no angles)
  std::optional<Pose> plannedAxis;  // the axis planned on the bone (each cut's axis is measured off it)
  ReportedGlenoidFace glenoidAsOpened, glenoidNow;  // the glenoid face before the cuts and now (addGlenoidFaces)
  std::optional<ReamedSurfaceReport> seat;  // the reamed surface under the face at reamerPose (addSeat)
  std::vector<CutLogEntry> cuts;    // the log's rows, in order
  std::vector<bool> undone;         // beside `cuts` (or empty): the row's cut is not in the bone now (undone)
  std::string pngBase64;            // a picture of the view (PNG, base64); empty: none
  std::int64_t writtenUnixMs = 0;   // when (0: not said)
  std::string writtenBy = "ReamSim";
};

// Measures the glenoid face of both states about the landmarks' glenoid centre into `input` (nothing without
// one; `now` is skipped when it is `opened`). O(faces) each: ~4 ms at 400k.
void addGlenoidFaces(ReamReportInput& input, const BoneState& opened, const BoneState& now);

// Measures the seat of the reamer at input.reamerPose on `now` (measureReamedSurface) into `input`: nothing without
// a pose or for a reamer read from a mesh (no ideal face). O(faces).
void addSeat(ReamReportInput& input, const BoneState& now);

// The whole HTML document. Every text from the input is escaped; numbers are written in the C locale.
std::string reamReportHtml(const ReamReportInput& input);

}  // namespace reamsim
