#pragma once
// The thesis's contact query, kept as the correctness reference: bounding-box broad phase, then one ray per
// cutting-face vertex along the feed axis, brute force over all bone triangles.
//
// Known limitation (by design of the thesis method): only the face vertices are probed, so bone features
// thinner than the vertex spacing, or bone entering the reamer from the side, can be missed.
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct ThesisContactResult {
  // Broad phase: bone box vs the reamer's box grown by stepMm (a gap <= stepMm cannot hide outside it).
  // When false no rays are cast and contact is false.
  bool boxesOverlap = false;
  bool contact = false;      // some vertex inside the bone, or the smallest gap <= stepMm
  bool penetrating = false;  // some vertex inside the bone
  double minDistanceMm = std::numeric_limits<double>::infinity();  // 0 when penetrating; +inf: no hit
  double penetrationDepthMm = 0;  // max over inside vertices of the distance back (-feedAxis) to the surface
  std::optional<Vec3> contactPoint;  // hit point of the deepest vertex (back ray) or the closest one
  std::size_t insideVertices = 0;
  std::size_t raysCast = 0;  // forward + backward rays
};

// `feedAxis` need not be unit length (it is normalised; zero throws std::invalid_argument); stepMm >= 0.
ThesisContactResult thesisContactQuery(const TriangleMesh& bone, const Bounds& boneBounds,
                                       const TriangleMesh& cuttingSolidInBoneCoords,
                                       const std::vector<Vec3>& cuttingFaceVerticesInBoneCoords,
                                       const Vec3& feedAxis, double stepMm);

}  // namespace reamsim
