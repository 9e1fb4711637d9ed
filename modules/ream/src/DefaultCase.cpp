#include "reamsim/ream/DefaultCase.h"

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/Resources.h"

namespace reamsim {

DefaultBone loadDefaultBone() {
  DefaultBone bone;
  bone.meshPath = resourcePath(kDefaultBoneFile);
  bone.originalPath = resourcePath(kDefaultOriginalFile);
  ReadOptions options;
  options.units = Units::Millimetres;  // the repaired file is written in mm
  bone.mesh = readMesh(bone.meshPath, options).mesh;
  bone.glenoid = loadGlenoid(resourcePath(kDefaultGlenoidFile));
  return bone;
}

ScapulaLandmarks loadDefaultLandmarks() { return loadLandmarks(resourcePath(kDefaultLandmarksFile)); }

std::string defaultPlanPath() { return resourcePath(kDefaultPlanFile); }
std::string reamerPresetsPath() { return resourcePath("reamers.json"); }

}  // namespace reamsim
