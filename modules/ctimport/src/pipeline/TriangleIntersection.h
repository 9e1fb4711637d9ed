#pragma once
// The exact two-triangle test behind findSelfIntersections, for callers that move vertices before
// committing (decimation). Triangles are given by vertex ids (equal ids = shared vertex) and positions.
// Implemented in CgalSelfIntersections.cpp, the module's one CGAL translation unit.
#include <array>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::ct::detail {

using Corners = std::array<Vec3, 3>;

// True if the triangles meet other than along what they share (CGAL PMP's rules, see SelfIntersections.h).
bool trianglesIntersect(const Triangle& a, const Corners& pa, const Triangle& b, const Corners& pb);
// Zero area (collinear corners), exactly.
bool triangleIsDegenerate(const Corners& p);

}  // namespace reamsim::ct::detail
