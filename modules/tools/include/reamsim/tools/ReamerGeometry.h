#pragma once
// Parametric reamer geometry in the reamer-local frame: the apex (tip) of the cutting face at the origin,
// feed direction +Z (into the bone). The cutting solid is the volume a spinning reamer removes:
//   spherical face: cap of the sphere of radius R centred at (0,0,-R), chord diameter D, z in [-h, 0],
//                   h = R - sqrt(R^2 - (D/2)^2), followed by a cylinder of diameter D from z=-h to -h-bodyLength;
//   flat face (R infinite): a disc at z=0 followed by the cylinder from z=0 to z=-bodyLength.
// All polygon vertices lie ON the sphere/circle (inscribed polygons), so the mesh volume is slightly below
// the ideal one and converges to it as segments/rings grow.
#include <vector>

#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Throws std::invalid_argument with a clear message when the spec cannot describe a reamer
// (D/2 > R, non-positive or non-finite sizes, segments < 3, rings < 1, flat with zero body length...).
void validateReamerSpec(const ReamerSpec& spec);

// Height of the spherical cap (0 for a flat reamer).
double capHeight(const ReamerSpec& spec);

// Closed, 2-manifold, outward-oriented, convex cutting solid: spec.rings rings on the face (pole at the apex
// as a triangle fan; a flat face also gets `rings` concentric rings so that ray casts from its vertices
// sample the whole disc), spec.segments vertices around the rim and the body; a spherical cap's inner rings
// have fewer, in proportion to their radius (no needle facets at the apex).
TriangleMesh buildCuttingSolid(const ReamerSpec& spec);

// Closed-form volume of the ideal (smooth) cutting solid, mm^3.
double idealCuttingVolume(const ReamerSpec& spec);

// The vertices of the cutting face (cap or disc) in local coordinates: the apex first, then ring by ring
// from the apex outwards (as many per ring as buildCuttingSolid() gives it). They are the first vertices of
// buildCuttingSolid().
std::vector<Vec3> cuttingFaceVertices(const ReamerSpec& spec);

// Display-only parts: the guide pin sticks out of the tip along +Z; the shaft continues behind the body
// along -Z. A part with zero diameter or length is an empty mesh.
struct ReamerDisplayParts {
  TriangleMesh guidePin;
  TriangleMesh shaft;
};
ReamerDisplayParts buildDisplayParts(const ReamerSpec& spec);

// Closed, outward-oriented cylinder about the Z axis between z0 < z1 (inscribed polygon, capped by fans).
TriangleMesh buildClosedCylinder(double radius, double z0, double z1, int segments);

}  // namespace reamsim
