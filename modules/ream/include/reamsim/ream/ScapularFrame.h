#pragma once
// The scapular frame and the version and inclination of a reaming axis in it (docs/PLANNING.md).
//
// From the three landmarks (reamsim/core/ScapulaLandmarks.h: glenoid centre GC, trigonum scapulae TS,
// inferior angle AI) and the body side:
//   lateral  L = unit(GC - TS): the scapular axis (Friedman's line, taken in 3D);
//   superior S = unit(the part of TS - AI normal to L): in the scapular plane (GC, TS, AI), away from AI;
//   anterior A = S x L for a right scapula, L x S for a left one, so that L, A and S are the patient's
//            lateral, anterior and superior on either side.
// For a direction o pointing out of the glenoid (towards the humeral head; the reamer feeds along -o):
//   version     = atan2(o.A, o.L), the angle in the transverse plane (L, A): > 0 anteversion, < 0 retroversion;
//   inclination = atan2(o.S, o.L), the angle in the scapular plane (L, S): > 0 superior tilt, < 0 inferior.
// The inverse, o ~ L + tan(version) A + tan(inclination) S, gives back both angles exactly (up to rounding).
#include <string>

#include "reamsim/core/ScapulaLandmarks.h"
#include "reamsim/core/PatientFrame.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

struct ScapularFrame {
  Vec3 origin;  // the glenoid centre
  Vec3 lateral, anterior, superior;  // orthonormal
  BodySide side = BodySide::Right;
};

struct AxisAngles {
  double versionDeg = 0;
  double inclinationDeg = 0;
};

// Preconditions first, each a std::invalid_argument that names the landmark and the problem: every
// landmark present and finite, the side given, the points at least 5 mm apart and not within 5 degrees of
// one line (the plane would be undefined or swing with a millimetre of picking).
ScapularFrame scapularFrame(const ScapulaLandmarks& landmarks);

// Angles of the outward direction `outward` (any length). std::invalid_argument when it is zero or not
// finite, or points medially (o.L <= 0: version and inclination are defined within +-90 degrees).
AxisAngles axisAngles(const ScapularFrame& frame, const Vec3& outward);

// The same for a reamer's feed axis (into the bone, as Pose::axis): the angles of its opposite.
inline AxisAngles feedAxisAngles(const ScapularFrame& frame, const Vec3& feedAxis) {
  return axisAngles(frame, feedAxis * -1.0);
}

// The unit outward direction with these angles (each finite and within +-89 degrees, else
// std::invalid_argument).
Vec3 outwardAxisFor(const ScapularFrame& frame, const AxisAngles& angles);

// The reamer aimed through the glenoid centre along these angles: its tip `clearanceMm` out along the
// outward direction (clear of the glenoid), feeding along the inward one.
Pose aimedReamerPose(const ScapularFrame& frame, const AxisAngles& angles, double clearanceMm);

// The angle between two axes in degrees (0..180), e.g. the reamer's off the planned one; 0 for a zero axis.
double axisDeviationDeg(const Vec3& a, const Vec3& b);

// The side a bone in a known patient frame must be (docs/CT_IMPORT.md: LPS +x toward the patient's left, RAS
// toward the right): the scapular axis GC - TS points laterally, away from the midline, so its x says which
// side. nullopt when the frame is unspecified, a point is missing, or the axis runs within 17 degrees of the
// sagittal plane (|x| < 0.3 of its length: too close to tell).
std::optional<BodySide> sideFromPatientFrame(PatientFrame frame, const ScapulaLandmarks& landmarks);

// Landmark files (JSON, docs/PLANNING.md): "side" and the three points, each optional (a half-placed set, or
// none, is read back as written), and "method" (free text); any other key is an error (a misspelt key must not
// read as a point left unplaced). loadLandmarks throws InputError naming the file and the field.
ScapulaLandmarks loadLandmarks(const std::string& path);
ScapulaLandmarks parseLandmarksJson(const std::string& text, const std::string& source);
std::string landmarksToJson(const ScapulaLandmarks& landmarks, const std::string& method = {});

// A bone's planning as one file: its landmarks and, optionally, the reaming axis planned on it
// ("planned_axis": {"tip": [x, y, z], "axis": [x, y, z]}: through `tip` (the glenoid centre), feeding along
// `axis`, normalised on reading; a zero or non-finite axis is an error). The landmark functions above read and
// write the same files without the axis.
struct BonePlanning {
  ScapulaLandmarks landmarks;
  std::optional<Pose> plannedAxis;
};
bool operator==(const BonePlanning& a, const BonePlanning& b);  // to the bit
inline bool operator!=(const BonePlanning& a, const BonePlanning& b) { return !(a == b); }
BonePlanning planningOf(const class BoneNode& bone);  // its landmarks and planned axis
void applyPlanning(class BoneNode& bone, const BonePlanning& planning);  // both set, one report to observers
BonePlanning loadPlanning(const std::string& path);
BonePlanning parsePlanningJson(const std::string& text, const std::string& source);
std::string planningToJson(const BonePlanning& planning, const std::string& method = {});

}  // namespace reamsim
