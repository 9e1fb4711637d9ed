// Where Aim may place the reamer without cutting (reamsim/ream/ClearPlacement.h): the nearest clear pose outward
// along the axis, on the bundled scapula with the engine the reaming loop uses.
#include <gtest/gtest.h>

#include <stdexcept>

#include "reamsim/ream/Approach.h"
#include "reamsim/ream/ClearPlacement.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ReamBackends.h"
#include "reamsim/tools/ReamerPresets.h"
#include "reamsim/tools/ReamerFile.h"
#include "reamsim/mesh/WindingNumber.h"
#include "../collision/TestMeshes.h"

namespace reamsim {
namespace {

struct Scene {
  ReamerSpec spec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  BoneState bone = BoneState::fromMesh(loadDefaultBone().mesh);
  Pose start = loadPlan(defaultPlanPath()).feed->start;  // in front of the glenoid, clear of it
  ReamEngine engine{std::make_shared<const TriangleMesh>(cuttingSolidFor(spec)), makeBvhContactBackend(),
                    localCutBackendFactory(), spec};
  double approach = *engine.advanceToContactMm(bone, 1, start, 100);
};

TEST(ClearPlacement, AClearPoseIsKept) {
  Scene s;
  const ClearPlacement c = findClearPlacement(s.engine, s.bone, 1, s.start);
  EXPECT_EQ(c.outcome, ClearPlacement::Outcome::AsAsked);
  EXPECT_EQ(c.queries, 2);  // touching? then overlapping at all?
  EXPECT_FALSE(c.overlapSearch);
  EXPECT_EQ(c.pose.tip.x, s.start.tip.x);
}

// A pose 2.2 mm past the first contact (the reamer in the glenoid) retreats to just outside it: clear at the
// answer, touching a little inward of it, and about as far out as the contact along the feed.
TEST(ClearPlacement, AnOverlappingPoseRetreatsToTheNearestClearPose) {
  Scene s;
  ASSERT_GT(s.approach, 0.5);
  const Pose inside = advancedAlongAxis(s.start, s.approach + 2.2);
  ASSERT_EQ(s.engine.overlapsAt(s.bone, 1, inside), true);
  const ClearPlacement c = findClearPlacement(s.engine, s.bone, 1, inside, 60, 0.5, 0.05);
  ASSERT_EQ(c.outcome, ClearPlacement::Outcome::Retreated);
  EXPECT_EQ(s.engine.overlapsAt(s.bone, 1, c.pose), false);
  EXPECT_EQ(s.engine.overlapsAt(s.bone, 1, advancedAlongAxis(c.pose, 0.06)), true);  // the margin, and ~2 µm
  EXPECT_NEAR(c.retreatMm, 2.2 + 0.05, 0.01);  // the feed meets the bone first where it leaves it last
  EXPECT_EQ(c.queries, 1 + 5 + 8 + 1 + 1);  // at the pose, five steps out, the bisection, the margin, the check
  EXPECT_FALSE(c.overlapSearch);
  EXPECT_NEAR(norm(c.pose.tip - advancedAlongAxis(inside, -c.retreatMm).tip), 0.0, 1e-12);
}

// Deep in the bone along its own axis, nothing within reach is clear: nothing is placed.
TEST(ClearPlacement, NoRoomWithinReachPlacesNothing) {
  Scene s;
  const Pose deep = advancedAlongAxis(s.start, s.approach + 6.0);
  const ClearPlacement c = findClearPlacement(s.engine, s.bone, 1, deep, 2.2, 0.5);
  EXPECT_EQ(c.outcome, ClearPlacement::Outcome::NoRoom);
  EXPECT_EQ(c.queries, 1 + 5);  // the last step ends at the reach (2.2 mm), not past it
  EXPECT_THROW(findClearPlacement(s.engine, s.bone, 1, deep, 0.0), std::invalid_argument);
  EXPECT_THROW(findClearPlacement(s.engine, s.bone, 1, deep, 10, 0.5, -1), std::invalid_argument);
  EXPECT_THROW(findClearPlacement(s.engine, s.bone, 1, deep, 1e9, 1e-3), std::invalid_argument);
}

// Clear means no bone to cut, not only no surface crossed: a reamer wholly inside a closed bone, or a bone
// fragment (a CT island) wholly inside the reamer, is not clear (a placement there would cut a cavity or take
// the fragment).
TEST(ClearPlacement, EnclosedReamerOrBoneIsNotClear) {
  const ReamerSpec spec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  const auto solid = std::make_shared<const TriangleMesh>(cuttingSolidFor(spec));
  ReamEngine engine{solid, makeBvhContactBackend(), localCutBackendFactory(), spec};
  const Bounds reach = computeBounds(*solid);  // the solid about its tip at the origin
  const Pose asked{{0, 0, 0}, {0, 0, 1}, 0};   // feeding along +z: a retreat goes along -z
  const Vec3 middle = (reach.min + reach.max) * 0.5;

  // The reamer in the middle of a closed block 40 mm larger each way: no surface near it.
  const Vec3 pad{40, 40, 40};
  const BoneState block = BoneState::fromMesh(test::makeBox(reach.min - pad, reach.max + pad));
  ASSERT_EQ(engine.touchesAt(block, 1, asked), false);  // no surface near it
  ASSERT_EQ(engine.overlapsAt(block, 1, asked), true);
  const ClearPlacement out = findClearPlacement(engine, block, 1, asked, 150, 0.5, 0.05);
  ASSERT_EQ(out.outcome, ClearPlacement::Outcome::Retreated);
  EXPECT_TRUE(out.overlapSearch);  // touching nothing where it was asked
  // Out through the block's -z face, the tip (the solid's top) the margin past it: no farther than needed.
  EXPECT_NEAR(reach.max.z - out.retreatMm, block.bounds().min.z - 0.05, 0.01) << out.retreatMm;
  EXPECT_EQ(engine.overlapsAt(block, 1, out.pose), false);
  EXPECT_EQ(findClearPlacement(engine, block, 1, asked, 20).outcome, ClearPlacement::Outcome::NoRoom);

  // A 1 mm fragment on the axis inside the reamer's solid (every corner inside it: no surface crossed).
  ReamEngine engine2{solid, makeBvhContactBackend(), localCutBackendFactory(), spec};
  const TriangleMesh cube = test::makeBox(middle - Vec3{0.5, 0.5, 0.5}, middle + Vec3{0.5, 0.5, 0.5});
  for (const Vec3& corner : cube.vertices) ASSERT_GT(windingNumber(*solid, corner), 0.5);
  const BoneState fragment = BoneState::fromMesh(cube);
  ASSERT_EQ(engine2.touchesAt(fragment, 1, asked), false);
  ASSERT_EQ(engine2.overlapsAt(fragment, 1, asked), true);
  const ClearPlacement off = findClearPlacement(engine2, fragment, 1, asked);
  ASSERT_EQ(off.outcome, ClearPlacement::Outcome::Retreated);
  EXPECT_TRUE(off.overlapSearch);
  EXPECT_EQ(engine2.overlapsAt(fragment, 1, off.pose), false);
  // Left below the tip (the cutting face's apex on the axis), the margin clear of it.
  EXPECT_NEAR(off.retreatMm, reach.max.z - (middle.z - 0.5) + 0.05, 0.02);
}

}  // namespace
}  // namespace reamsim
