#pragma once
// The glenoid of a scapula mesh, found from the geometry: the concave, near-spherical articular
// surface at the lateral angle. See docs/DEFAULT_CASE.md for the method and its parameters.
#include <string>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct GlenoidSearchOptions {
  Vec3 lateral{0, 0, 1};      // lateral direction of the bone's frame (OpenSim: +Z for a right scapula)
  double lateralBandMm = 35;  // candidates lie within this distance of the most lateral point
  double patchRadiusMm = 13;  // radius of the patch fitted with a sphere
  double minFacingLateral = 0.5;  // min cosine between a candidate's normal and `lateral`
  double minSphereRadiusMm = 15, maxSphereRadiusMm = 80;
  double fossaRadiusMm = 22;         // the fossa grown from the best patch stays within this distance
  double onSphereToleranceMm = 1.0;  // ...and within this distance of the patch's sphere
};

struct GlenoidFrame {
  Vec3 centre;        // on the bone surface, centre of the best-fitting concave patch
  Vec3 outwardAxis;   // unit, from the bone towards the humeral head (the reamer feeds along -outwardAxis)
  double sphereRadiusMm = 0;  // radius of the best-fit sphere of the patch
  double rmsResidualMm = 0;   // how spherical the patch is
  std::size_t patchVertices = 0;
};

// Throws std::runtime_error if no concave, lateral-facing patch is found.
GlenoidFrame findGlenoid(const TriangleMesh& bone, const GlenoidSearchOptions& options = {});

GlenoidFrame loadGlenoid(const std::string& jsonPath);  // throws InputError
std::string glenoidToJson(const GlenoidFrame& frame, const std::string& method);

}  // namespace reamsim
