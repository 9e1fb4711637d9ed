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
  EXPECT_EQ(c.queries, 1);
  EXPECT_EQ(c.pose.tip.x, s.start.tip.x);
}

// A pose 2.2 mm past the first contact (the reamer in the glenoid) retreats to just outside it: clear at the
// answer, touching a little inward of it, and about as far out as the contact along the feed.
TEST(ClearPlacement, AnOverlappingPoseRetreatsToTheNearestClearPose) {
  Scene s;
  ASSERT_GT(s.approach, 0.5);
  const Pose inside = advancedAlongAxis(s.start, s.approach + 2.2);
  ASSERT_EQ(s.engine.touchesAt(s.bone, 1, inside), true);
  const ClearPlacement c = findClearPlacement(s.engine, s.bone, 1, inside, 60, 0.5, 0.05);
  ASSERT_EQ(c.outcome, ClearPlacement::Outcome::Retreated);
  EXPECT_EQ(s.engine.touchesAt(s.bone, 1, c.pose), false);
  EXPECT_EQ(s.engine.touchesAt(s.bone, 1, advancedAlongAxis(c.pose, 0.06)), true);  // the margin, and ~2 µm
  EXPECT_NEAR(c.retreatMm, 2.2 + 0.05, 0.01);  // the feed meets the bone first where it leaves it last
  EXPECT_EQ(c.queries, 1 + 5 + 8 + 1);  // at the pose, five steps out, the bisection, the margin
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

}  // namespace
}  // namespace reamsim
