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

RepairResult repairMesh(const TriangleMesh& input, const RepairOptions& options = {});

std::string toText(const RepairReport& report);
std::string toJson(const RepairReport& report, int indent = 2);

}  // namespace reamsim
