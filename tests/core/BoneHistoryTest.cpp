#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "reamsim/core/BoneHistory.h"

using namespace reamsim;

namespace {
// Removes the triangle in slot `slot` (a small, distinguishable edit).
BoneState without(const BoneState& s, std::uint32_t slot) {
  MeshDelta d;
  d.removedTriangles = {slot};
  return s.applyDelta(d);
}
void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
}
}  // namespace

TEST(BoneHistory, UndoRedoRestoreTheExactMeshes) {
  const BoneState s0 = BoneState::fromMesh(test::grid(6));
  BoneHistory h(s0, "import");
  const TriangleMesh m0 = s0.toMesh();
  EXPECT_FALSE(h.canUndo());
  EXPECT_FALSE(h.canRedo());
  const std::uint64_t r0 = h.currentRevision();

  const std::uint64_t r1 = h.commit(without(h.current(), 3), "cut 1");
  const TriangleMesh m1 = h.current().toMesh();
  const std::uint64_t r2 = h.commit(without(h.current(), 7), "cut 2");
  const TriangleMesh m2 = h.current().toMesh();
  EXPECT_LT(r0, r1);
  EXPECT_LT(r1, r2);
  EXPECT_EQ(h.size(), 3u);
  EXPECT_EQ(h.currentEntry().label, "cut 2");

  EXPECT_TRUE(h.undo());
  expectSameMesh(h.current().toMesh(), m1);
  EXPECT_TRUE(h.undo());
  expectSameMesh(h.current().toMesh(), m0);
  EXPECT_FALSE(h.undo());
  EXPECT_TRUE(h.canRedo());
  EXPECT_TRUE(h.redo());
  EXPECT_TRUE(h.redo());
  EXPECT_FALSE(h.redo());
  expectSameMesh(h.current().toMesh(), m2);
  EXPECT_EQ(h.currentRevision(), r2);
}

TEST(BoneHistory, CommitAfterUndoDropsTheRedoBranch) {
  BoneHistory h(BoneState::fromMesh(test::grid(4)));
  h.commit(without(h.current(), 1), "a");
  const std::uint64_t rb = h.commit(without(h.current(), 2), "b");
  h.undo();
  const std::uint64_t rc = h.commit(without(h.current(), 5), "c");
  EXPECT_FALSE(h.canRedo());
  EXPECT_EQ(h.size(), 3u);
  EXPECT_EQ(h.entries()[2].label, "c");
  EXPECT_GT(rc, rb);  // revisions are never reused
  EXPECT_EQ(h.find(rb), nullptr);
  ASSERT_NE(h.find(rc), nullptr);
  EXPECT_EQ(h.find(rc)->label, "c");
  EXPECT_FALSE(h.current().isTriangleLive(5));
  EXPECT_TRUE(h.current().isTriangleLive(2));
}

TEST(BoneHistory, ResetForgetsEverythingButKeepsRevisionsIncreasing) {
  BoneHistory h(BoneState::fromMesh(test::box(1, 1, 1)));
  const std::uint64_t r = h.commit(BoneState{}, "emptied");
  h.reset(BoneState::fromMesh(test::box(2, 2, 2)), "reimport");
  EXPECT_EQ(h.size(), 1u);
  EXPECT_FALSE(h.canUndo());
  EXPECT_GT(h.currentRevision(), r);
  EXPECT_NEAR(h.current().volume(), 8, 1e-12);
}
