// The default case end to end, through the document: ≥ 20 feed steps of 0.1–0.25 mm into the glenoid;
// after every step the removed volume equals V_before − V_after and the bone is closed, outward and
// free of self-intersections; undo restores the previous bone exactly.
#include <gtest/gtest.h>

#include <cstdio>

#include "ReamFixture.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim {
namespace {

TEST(DefaultPlan, EveryStepKeepsBookkeepingAndInvariants) {
  const DefaultBone bone = loadDefaultBone();
  const ReamPlan plan = loadPlan(defaultPlanPath());
  ASSERT_TRUE(plan.feed.has_value());
  EXPECT_GE(plan.feed->count, 20);
  EXPECT_GE(plan.feed->stepMm, 0.1);
  EXPECT_LE(plan.feed->stepMm, 0.25);

  test::ReamScene scene(bone.mesh, loadPreset(plan.reamer, reamerPresetsPath()));
  std::size_t contacts = 0, roundedSelfIntersecting = 0;
  double previousVolume = scene.bone->current().volume();
  for (const Pose& pose : plan.expandedPoses()) {
    const TriangleMesh before = scene.bone->current().toMesh();
    const ReamStepOutcome out = scene.controller->moveTo(pose);
    const double after = scene.bone->current().volume();
    // Bookkeeping: the removed volume (from bone ∩ tool) equals V_before − V_after of the document's bone.
    EXPECT_NEAR(out.entry.removedMm3, previousVolume - after, 1e-6 * std::max(1.0, out.entry.removedMm3))
        << "step " << out.entry.stepIndex;
    previousVolume = after;
    if (!out.cut.changed) continue;
    ++contacts;
    const BoneInvariants inv = scene.controller->checkBone();
    EXPECT_TRUE(inv.closed) << "step " << out.entry.stepIndex;
    EXPECT_TRUE(inv.outwardOriented) << "step " << out.entry.stepIndex;
    EXPECT_FALSE(inv.selfIntersectsExact) << "step " << out.entry.stepIndex;
    roundedSelfIntersecting += inv.selfIntersectsRounded;
    EXPECT_TRUE(scene.alerts->has(AlertKind::Contact));
    // Undo restores the previous bone exactly, redo the cut.
    const TriangleMesh cut = scene.bone->current().toMesh();
    ASSERT_TRUE(scene.bone->undo());
    const TriangleMesh undone = scene.bone->current().toMesh();
    EXPECT_EQ(undone.vertices, before.vertices);
    EXPECT_EQ(undone.triangles, before.triangles);
    ASSERT_TRUE(scene.bone->redo());
    EXPECT_EQ(scene.bone->current().toMesh().triangles, cut.triangles);
  }
  EXPECT_GE(contacts, 15u);
  EXPECT_GT(scene.log->entries().back().cumulativeMm3, 100.0);
  std::printf("[default plan] %zu steps, %zu cuts, %.3f mm3 removed, faces %zu -> %zu, rounded copy "
              "self-intersecting after %zu cuts\n",
              scene.log->size(), contacts, scene.log->entries().back().cumulativeMm3, bone.mesh.triangles.size(),
              scene.bone->current().liveTriangleCount(), roundedSelfIntersecting);
  const StorageStats storage = scene.bone->history().storageStats();
  std::printf("[default plan] history of %zu states: %zu unique bytes vs %zu if copied\n", scene.bone->history().size(),
              storage.uniqueBytes, storage.logicalBytes);
  EXPECT_LT(storage.uniqueBytes, storage.logicalBytes / 3);
}

}  // namespace
}  // namespace reamsim
