#pragma once
// The bundled default case: the real OpenSim scapula (CC BY 3.0), repaired to a closed solid in mm,
// its glenoid frame, and a feed plan onto the glenoid. See resources/README.md and docs/DEFAULT_CASE.md.
#include <string>

#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/ream/Glenoid.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {

struct DefaultBone {
  TriangleMesh mesh;      // repaired, closed, mm
  std::string meshPath;
  std::string originalPath;  // the unrepaired source mesh (metres), kept for display and comparison
  GlenoidFrame glenoid;
};

// The bundled scapula's landmarks (resources/bones/scapula_R_landmarks.json; how they were placed is in
// the file and in docs/PLANNING.md). Throws InputError when the file is missing or damaged.
ScapulaLandmarks loadDefaultLandmarks();

DefaultBone loadDefaultBone();
std::string defaultPlanPath();
std::string reamerPresetsPath();

// Resource names, relative to resourceDir().
inline constexpr const char* kDefaultBoneFile = "bones/scapula_R_repaired.ply";
inline constexpr const char* kDefaultOriginalFile = "bones/scapula_R_opensim.vtp";
inline constexpr const char* kDefaultGlenoidFile = "bones/scapula_R_glenoid.json";
inline constexpr const char* kDefaultLandmarksFile = "bones/scapula_R_landmarks.json";
inline constexpr const char* kDefaultPlanFile = "plans/default_plan.json";

}  // namespace reamsim
