#pragma once
// Closed, outward-oriented primitive solids for analytic tests and benchmarks (blocks of known volume).
#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Axis-aligned box; each face split into `divisions`² quads (2 triangles each) so that cuts are local.
TriangleMesh buildBox(const Bounds& box, int divisions = 1);

}  // namespace reamsim
