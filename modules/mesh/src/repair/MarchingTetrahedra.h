#pragma once
#include "ScalarGrid.h"
#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Zero set of the grid's piecewise-linear interpolant on the Kuhn subdivision (6 tetrahedra per cell,
// all sharing the cell's main diagonal, which makes the subdivision conforming across cells).
// Output triangles are oriented with normals pointing towards positive values (outside).
// Checks `progress` before each layer of cells.
TriangleMesh marchingTetrahedra(const ScalarGrid& grid, const StageProgress& progress = {});

}  // namespace reamsim
