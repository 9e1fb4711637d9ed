#pragma once
// Repair on import: always reported, never silent. Cheap topological repairs first (merge duplicate
// vertices, drop degenerate and duplicate faces, orient consistently, close small holes, orient outward);
// when the result is still not a clean solid (open, non-orientable, self-intersecting), a volumetric
// remesh (see VolumetricRemesh.h) rebuilds a closed, oriented, self-intersection-free surface and the
// report says how far it lies from the input.
#include <optional>
#include <string>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Validation.h"
#include "reamsim/mesh/VolumetricRemesh.h"

namespace reamsim {

struct RepairOptions {
  std::size_t maxHoleBoundaryEdges = 40;  // holes with at most this many edges are triangulated
  bool allowRemesh = true;
  RemeshOptions remesh;
  // Stages and fractions of the whole repair (the remesh's included), and (1.0, "done") on every return;
  // returning false stops the repair at its next check with RepairCancelled. Checks lie between stages and
  // inside the long ones (StageProgress): slices of the remesh's band, layers of marching tetrahedra,
  // thousands of decimation collapses, slices of the distances to the input, slabs of each validation's
  // self-intersection count; a second or less apart at millions of triangles.
  RepairProgress progress;
};

struct RepairReport {
  ValidationReport before;
  ValidationReport after;
  std::size_t mergedVertices = 0;
  std::size_t removedFaces = 0;       // degenerate or duplicate faces removed by soup repair
  bool orientableWithoutSplitting = true;
  std::size_t holesClosed = 0;
  std::size_t holesLeftOpen = 0;
  bool flippedToOutward = false;
  bool remeshed = false;
  std::optional<RemeshStats> remesh;
  std::vector<std::string> actions;   // every change made, in order, in words
  bool success() const { return after.isCleanSolid(); }
};

struct RepairResult {
  TriangleMesh mesh;
  RepairReport report;
};

// Throws RepairCancelled when `options.progress` asks it to stop; never for a mesh it cannot repair (the
// report says so).
RepairResult repairMesh(const TriangleMesh& input, const RepairOptions& options = {});

// The repair used on import (the GUI's Open, `reamsim-cli ream`, the CT pipeline): the defaults, with the
// remesh's grid coarsened where its band would exceed 2.5 million candidate points (the 400k CT skull:
// ~1 mm instead of 0.5, about 4 million triangles in about a minute instead of 17 million in four; the
// bundled scapula's original stays at 0.5 mm). `reamsim-cli repair` keeps the grid it is given.
RepairOptions importRepairOptions();

std::string toText(const RepairReport& report);
std::string toJson(const RepairReport& report, int indent = 2);

}  // namespace reamsim
