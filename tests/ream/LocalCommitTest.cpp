// The local engine's cut reaches the document as a state derived from the bone by the cut's own delta:
// the loop commits it without diffing the whole mesh, the new state shares the bone's untouched storage,
// the BVH collision engine follows exactly the slots the cut changed, and a backend that reads the whole
// mesh (the thesis's rays) sees the bone as cut.
#include <gtest/gtest.h>

#include <cmath>

#include "ReamFixture.h"
#include "reamsim/collision/BoneCollider.h"
#include "reamsim/csg/LocalSubtractor.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim {
namespace {

TriangleMesh placed(const TriangleMesh& local, const Pose& pose) {
  TriangleMesh m = local;
  const RigidTransform t = toTransform(pose);
  for (Vec3& p : m.vertices) p = t.apply(p);
  return m;
}

TEST(LocalCutCommit, ACutIsALocalEditOfTheBoneState) {
  const DefaultBone bone = loadDefaultBone();
  const ReamerSpec spec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  test::ReamScene s(bone.mesh, spec, localCutBackendFactory(), makeBvhContactBackend());
  LocalSubtractor alone(bone.mesh);  // the same engine outside the loop, on the same cuts
  alone.setReferenceTool(*s.reamer->cuttingVolume());  // as the loop's engine: the same clean-up bound
  const ReamerModel reamer = ReamerModel::fromCuttingVolume(*s.reamer->cuttingVolume(), &spec);
  const Vec3 out = bone.glenoid.outwardAxis;
  for (int step = 1; step <= 3; ++step) {
    const Pose pose{bone.glenoid.centre + out * (1.0 - 0.6 * step), -out, 0};
    const BoneState before = s.bone->current();
    // What the collision engine (following the earlier cuts) sees must be what a fresh tree sees.
    const std::size_t touchedFresh = BoneCollider(before).overlap(reamer, toTransform(pose)).touchedSlots.size();
    const ReamStepOutcome o = s.controller->moveTo(pose);
    ASSERT_TRUE(o.cut.changed) << "step " << step;
    EXPECT_EQ(o.contact.touchedFaces, touchedFresh) << "step " << step;

    const BoneState& after = s.bone->current();
    const SlotChanges changed = BoneState::changedTriangleSlots(before, after);
    EXPECT_FALSE(changed.removed.empty());
    EXPECT_FALSE(changed.added.empty());
    EXPECT_LT(changed.removed.size() + changed.added.size(), after.liveTriangleCount() / 5) << "step " << step;
    // Most storage is shared with the state before: the cut copied only the chunks it touched.
    const StorageStats storage = measureStorage({&before, &after});
    EXPECT_LT(storage.uniqueBytes, 1.5 * before.storageBytes()) << "step " << step;

    alone.subtract(placed(*s.reamer->cuttingVolume(), pose));
    EXPECT_EQ(after.liveTriangleCount(), alone.faceCount()) << "step " << step;
    EXPECT_EQ(after.volume(), alone.volumeMm3()) << "step " << step;
    EXPECT_NEAR(before.volume() - after.volume(), o.cut.removedMm3, 1e-9 * o.cut.removedMm3);
  }
}

// A ring of six cuts 1 mm deep (3 mm off the axis, swept from one to the next) leaves a floor at z = -1
// under the whole 20 mm face; from z = 0.5 every ray then reaches that floor (1.5 mm). Rays on the uncut
// block would stop at its top (0.5 mm).
TEST(LocalCutCommit, TheThesisRaysSeeTheBoneAsCut) {
  test::ReamScene s(test::blockBelowZ0(), test::flatReamer20(), localCutBackendFactory(), makeThesisContactBackend());
  for (int k = 0; k < 6; ++k) {
    const double a = k * M_PI / 3;
    ASSERT_TRUE(s.controller->moveTo(Pose{{3 * std::cos(a), 3 * std::sin(a), -1.0}, {0, 0, -1}, 0}).cut.changed);
  }
  const ReamStepOutcome above = s.controller->moveTo(Pose{{0, 0, 0.5}, {0, 0, -1}, 0});
  ASSERT_TRUE(above.contact.boxesOverlap);
  // The floor 1 mm down, to the band clean-up's deviation (1 µm per operation).
  EXPECT_NEAR(above.contact.minDistanceMm, 1.5, 1e-3);
}

}  // namespace
}  // namespace reamsim
