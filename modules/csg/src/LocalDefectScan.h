#pragma once
// Whole-bone scans the local engine runs once at construction (and the invariant checks for tests):
// which faces are defects a local Boolean must not touch. Implemented in CgalLocalDefects.cpp.
#include <cstdint>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::csg {

enum DefectFlag : std::uint8_t {
  kSelfIntersecting = 1,
  kNonManifold = 2,  // on an edge used by 3+ faces, or traversed twice in the same direction
  kDegenerate = 4,   // repeated vertex or collinear corners
};

struct DefectScan {
  std::vector<std::uint8_t> flags;  // per triangle of the scanned mesh
  std::size_t borderEdges = 0;
  std::size_t selfIntersectingPairs = 0;
};

// `mesh` may be any triangle soup with valid indices.
DefectScan scanDefects(const TriangleMesh& mesh);

}  // namespace reamsim::csg
