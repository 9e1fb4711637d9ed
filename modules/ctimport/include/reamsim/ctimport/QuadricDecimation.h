#pragma once
// Garland–Heckbert edge-collapse decimation tuned for large isosurfaces: instead of one global priority
// queue (VTK's vtkQuadricDecimation takes ~6 s for 670k faces, CGAL's edge_collapse ~20 s), each pass
// collapses, in mesh order, the edges whose quadric error is below a quantile of the current errors, with at
// most one collapse per neighbourhood per pass. A collapse is refused if it would break the 2-manifold
// (link condition), flip or crush a neighbouring face, or touch a locked vertex, so a closed, oriented
// input stays closed and oriented. With `preventSelfIntersections` a collapse is also refused if one of
// the faces it creates meets another face (exact test against a grid of the current faces), so an input
// free of self-intersections stays free of them. The guard roughly doubles the cost; `guardedVertices`
// limits it to collapses touching flagged vertices (the import pipeline flags the places where an
// unguarded run went wrong).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::ct {

struct DecimationOptions {
  std::size_t targetFaces = 0;
  const std::vector<std::uint8_t>* lockedVertices = nullptr;  // one flag per input vertex; never collapsed
  double minNormalCosine = 0.2;   // refuse collapses that turn a face normal by more than ~78°
  double minTriangleQuality = 0.02;  // 2·area/(longest edge)²; refuse new faces worse than this and than before
  bool preventSelfIntersections = true;
  const std::vector<std::uint8_t>* guardedVertices = nullptr;  // one flag per input vertex; null = all
};

struct DecimationStats {
  std::size_t facesBefore = 0;
  std::size_t facesAfter = 0;
  int passes = 0;
  bool reachedTarget = false;
  std::vector<std::uint32_t> sourceVertex;  // for each output vertex, the input vertex it continues
};

// Input: a closed, consistently oriented 2-manifold triangle mesh. `keepGoing` is asked between passes;
// returning false stops early and returns the mesh as it is (still valid).
TriangleMesh decimateQuadric(const TriangleMesh& mesh, const DecimationOptions& options,
                             DecimationStats* stats = nullptr, const std::function<bool()>& keepGoing = {});

}  // namespace reamsim::ct
