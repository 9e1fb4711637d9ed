#pragma once
// The edit a slot comparison once missed: one triangle, removed and put back in its own slot with a new corner
// that takes the freed slot of the old one (applyDelta frees orphans before it allocates). Same slots, a moved
// corner: (0, 0, 0) becomes (0, 0, 1). Shared by the core and collision tests.
#include <gtest/gtest.h>

#include "reamsim/core/BoneState.h"

namespace reamsim::test {

struct MovedCornerEdit {
  BoneState before, after;
};

inline MovedCornerEdit movedCornerEdit() {
  TriangleMesh one;
  one.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  MovedCornerEdit e;
  e.before = BoneState::fromMesh(one, BoneState::Ordering::Preserve);
  MeshDelta d;
  d.removedTriangles = {0};
  d.addedVertices = {{0, 0, 1}};
  d.addedTriangles = {{MeshDelta::newVertex(0), 1, 2}};
  DeltaPlacement placement;
  e.after = e.before.applyDelta(d, &placement);
  EXPECT_EQ(placement.triangleSlots, std::vector<std::uint32_t>{0u});  // the same triangle slot
  EXPECT_EQ(placement.vertexSlots, std::vector<std::uint32_t>{0u});    // the freed vertex slot, taken again
  EXPECT_EQ(e.after.triangle(0), e.before.triangle(0));                // the same corner slots
  return e;
}

}  // namespace reamsim::test
