// How much bone a ream to depth would take, before anything is cut (reamsim/ream/RemovalPreview.h).
#include <gtest/gtest.h>

#include <stdexcept>

#include "ReamFixture.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/RemovalPreview.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim {
namespace {

// The preview removes what the reaming loop removes with the same steps (to the bit: the same engine and
// steps), on the bundled scapula at the default plan's start, and leaves the bone it was given as it was.
TEST(RemovalPreview, RemovesWhatTheLoopRemovesAndLeavesTheBone) {
  const ReamerSpec spec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  const Pose start = loadPlan(defaultPlanPath()).feed->start;
  test::ReamScene loop(loadDefaultBone().mesh, spec, localCutBackendFactory());
  loop.controller->moveTo(start, true);  // the reamer placed where the preview starts
  const BoneState before = loop.bone->current();
  const std::size_t facesBefore = before.liveTriangleCount();
  ReamEngine engine(loop.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory(), spec);
  const RemovalPreview p = previewReamToDepth(engine, before, start, 1.5, 0.2, 100);
  ASSERT_TRUE(p.approachMm);
  EXPECT_GT(*p.approachMm, 0.5);  // the plan starts clear of the bone
  EXPECT_EQ(before.liveTriangleCount(), facesBefore);
  EXPECT_EQ(loop.bone->current().liveTriangleCount(), facesBefore);

  const std::vector<Pose> poses = reamToDepthPoses(start, *p.approachMm, 1.5, 0.2);
  for (const Pose& pose : poses) loop.controller->moveTo(pose);
  const double removed = before.volume() - loop.bone->current().volume();
  EXPECT_GT(removed, 100.0);
  EXPECT_NEAR(p.removedMm3, removed, 1e-9 * removed);
  EXPECT_EQ(p.facesAfter, loop.bone->current().liveTriangleCount());
  EXPECT_NEAR(p.after.volume(), loop.bone->current().volume(), 1e-9 * removed);
  EXPECT_EQ(p.steps, poses.size());
  EXPECT_GE(p.cuts, poses.size() - 1);  // every feed step cuts
  EXPECT_EQ(p.depthMm, 1.5);

  // Deeper takes more; the same engine goes on from any bone it is given.
  const RemovalPreview deeper = previewReamToDepth(engine, before, start, 2.5, 0.2, 100);
  EXPECT_GT(deeper.removedMm3, p.removedMm3 + 50);
  EXPECT_EQ(deeper.approachMm, p.approachMm);
}

TEST(RemovalPreview, NothingInReachRemovesNothingAndBadArgumentsAreRefused) {
  const ReamerSpec spec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  Pose away = loadPlan(defaultPlanPath()).feed->start;
  away.tip = away.tip - away.axis * 100.0;  // backed off 100 mm...
  away.axis = away.axis * -1.0;             // ...and turned away from the glenoid
  const BoneState bone = BoneState::fromMesh(loadDefaultBone().mesh);
  auto volume = std::make_shared<const TriangleMesh>(buildCuttingSolid(spec));
  ReamEngine engine(volume, makeBvhContactBackend(), localCutBackendFactory(), spec);
  const RemovalPreview none = previewReamToDepth(engine, bone, away, 1.0, 0.2, 5);
  EXPECT_FALSE(none.approachMm);
  EXPECT_EQ(none.removedMm3, 0.0);
  EXPECT_EQ(none.steps, 0u);
  EXPECT_EQ(none.facesAfter, bone.liveTriangleCount());
  EXPECT_THROW(previewReamToDepth(engine, bone, away, 0, 0.2, 5), std::invalid_argument);
  EXPECT_THROW(previewReamToDepth(engine, bone, away, 1, -0.2, 5), std::invalid_argument);
  EXPECT_THROW(previewReamToDepth(engine, bone, away, 1, 0.2, 0), std::invalid_argument);
  ReamEngine collisionOnly(volume, makeBvhContactBackend(), CutBackendFactory{}, spec);
  EXPECT_THROW(previewReamToDepth(collisionOnly, bone, away, 1, 0.2, 5), std::invalid_argument);
}

// The seat a preview reports is the reamed surface of its bone at its last pose: what Measure seat says after the
// same ream to depth in the loop; deeper seats more of a face larger than the glenoid, up to what the glenoid
// offers; a reamer read from a mesh has no ideal face, and a preview without contact no seat.
TEST(RemovalPreview, TheSeatIsTheReamedSurfaceAtTheLastPose) {
  const ReamerSpec spec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  const Pose start = loadPlan(defaultPlanPath()).feed->start;
  test::ReamScene loop(loadDefaultBone().mesh, spec, localCutBackendFactory());
  loop.controller->moveTo(start, true);
  const BoneState before = loop.bone->current();
  ReamEngine engine(loop.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory(), spec);
  RemovalPreview p = previewReamToDepth(engine, before, start, 1.0, 0.2, 100);
  previewSeat(p, spec);
  ASSERT_TRUE(p.seat);
  const std::vector<Pose> poses = reamToDepthPoses(start, *p.approachMm, 1.0, 0.2);
  ASSERT_TRUE(p.lastPose);
  EXPECT_EQ(p.lastPose->tip, poses.back().tip);
  for (const Pose& pose : poses) loop.controller->moveTo(pose);
  const ReamedSurfaceReport measured = measureReamedSurface(loop.bone->current().toMesh(), spec, poses.back());
  EXPECT_NEAR(p.seat->seatedFraction, measured.seatedFraction, 1e-9);
  EXPECT_NEAR(p.seat->standoffRmsMm, measured.standoffRmsMm, 1e-9);
  EXPECT_GT(p.seat->seatedFraction, 0.05);

  RemovalPreview deeper = previewReamToDepth(engine, before, start, 3.0, 0.2, 100);
  previewSeat(deeper, spec);
  ASSERT_TRUE(deeper.seat);
  EXPECT_GT(deeper.seat->seatedFraction, p.seat->seatedFraction + 0.1);
  EXPECT_LT(deeper.seat->seatedFraction, 0.6);  // the 36 mm face overhangs this glenoid (~28 mm across)

  ReamerSpec fromMesh = spec;
  fromMesh.meshFile = "reamer.stl";
  RemovalPreview unseated = p;
  unseated.seat.reset();
  previewSeat(unseated, fromMesh);
  EXPECT_FALSE(unseated.seat);
  RemovalPreview none;
  previewSeat(none, spec);
  EXPECT_FALSE(none.seat);
}

}  // namespace
}  // namespace reamsim
