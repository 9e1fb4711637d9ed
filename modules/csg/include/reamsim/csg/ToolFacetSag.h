#pragma once
// How far a faceted tool's mesh stands off the smooth solid it approximates, estimated from the mesh alone.
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// For each face, the sum over its edges of (turn to the face across, in radians) × (the face's height over
// that edge) / 8, over edges that turn by less than 30 degrees (sharp edges, such as a reamer's rim, are
// features, not faceting); the largest over the faces. For a facet of a sphere's quad grid, L1 × L2 with
// turns L1 / R and L2 / R, that is (L1² + L2²) / 8R: its deepest point below the sphere. 0 for a mesh of
// planes and sharp edges only; an edge with no face across (an open or non-manifold mesh) adds nothing.
double toolFacetSagMm(const TriangleMesh& tool);

}  // namespace reamsim
