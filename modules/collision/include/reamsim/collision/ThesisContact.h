#pragma once
// The thesis's contact query, kept as the correctness reference: bounding-box broad phase, then one ray per
// cutting-face vertex along the feed axis, brute force over all bone triangles.
//
// Known limitation (by design of the thesis method): only the face vertices are probed, so bone features
// thinner than the vertex spacing, or bone entering the reamer from the side, can be missed.
#include <vector>

#include "reamsim/collision/ContactResult.h"
#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// `feedAxis` need not be unit length (it is normalised; zero throws std::invalid_argument); stepMm >= 0.
ContactResult thesisContactQuery(const TriangleMesh& bone, const Bounds& boneBounds,
                                 const TriangleMesh& cuttingSolidInBoneCoords,
                                 const std::vector<Vec3>& cuttingFaceVerticesInBoneCoords, const Vec3& feedAxis,
                                 double stepMm);

}  // namespace reamsim
