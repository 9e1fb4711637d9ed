#pragma once
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct SoupRepairResult {
  TriangleMesh mesh;          // merged, cleaned, oriented as far as possible, small holes closed
  TriangleMesh orientedSoup;  // after merging and orienting, before hole filling (input to a remesh)
  std::size_t verticesRemoved = 0;
  std::size_t facesRemoved = 0;
  bool orientableWithoutSplitting = true;
  std::size_t holesClosed = 0;
  std::size_t holesLeftOpen = 0;
  bool flippedToOutward = false;
};

SoupRepairResult repairSoupTopology(const TriangleMesh& input, std::size_t maxHoleBoundaryEdges);

}  // namespace reamsim
