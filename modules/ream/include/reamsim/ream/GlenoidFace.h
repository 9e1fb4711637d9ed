#pragma once
// Which way the glenoid face looks: the orientation of the bone's articular surface around the glenoid
// centre, measured on the mesh (docs/PLANNING.md "The glenoid's own version and inclination"). Its version
// and inclination in the scapular frame (axisAngles) are the glenoid's own, the figures a reaming plan
// corrects: measured on the bone as opened they are the native glenoid's; on the reamed bone, what the
// reaming left.
//
// The face is the connected piece of surface whose triangles' centroids lie within `radiusMm` of the centre
// and whose normals turn at most `maxTurnDeg` from the surface's mean normal near the centre (so the far side of
// a thin rim and the glenoid neck beyond a steep rim stay out), grown from the triangles nearest the centre over
// edges whose ends lie at the same two positions (shared vertex slots or not). Its direction is the sum of its triangles'
// vector areas, made unit: for a patch that is the vector area of its boundary loop, i.e. the normal of the
// rim's plane at that radius, whatever the fossa's depth. It is the central part of the face (10 mm: the glenoid is
// ~25 x 35 mm), not Friedman's rim-to-rim line; docs/PLANNING.md says how it moves with the radius and the centre.
#include <cstddef>

#include "reamsim/core/BoneState.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

struct GlenoidFaceOptions {
  double radiusMm = 10;    // within a glenoid's half-width (adult glenoids are ~25 mm wide, ~35 mm tall)
  double maxTurnDeg = 60;  // a face turned further from the mean normal near the centre is not the face
};

struct GlenoidFace {
  Vec3 outward;             // unit, the way the triangles face: out of the bone when it is oriented outward, as
                            // the import's repair orients a closed bone (an inside-out one reads as pointing medially)
  double areaMm2 = 0;       // of the triangles summed
  std::size_t triangles = 0;
  double radiusMm = 0;      // the radius it was measured within
  double centreGapMm = 0;   // from the glenoid centre to the nearest surface point (grows as the bone is reamed)
};

// Preconditions first, each a std::invalid_argument saying what is wrong: a finite centre, a radius within
// 2..40 mm, a turn within 1..89 degrees, a bone with surface; then a face must exist: some surface within the
// radius, and triangles near the centre whose vector areas do not cancel out. O(live triangles): ~4 ms at 400k
// (`bench cut --loop`, loop.glenoid_face).
GlenoidFace measureGlenoidFace(const BoneState& bone, const Vec3& centre, const GlenoidFaceOptions& options = {});

}  // namespace reamsim
