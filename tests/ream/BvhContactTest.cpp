// The reaming loop with the BVH contact engine (the default) against the thesis's rays: the same cuts, a
// true minimum distance (also after backing off a reamed hole), no Boolean while the reamer is clear of
// the bone, and sane contact points and depths on the real glenoid.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "ReamFixture.h"
#include "reamsim/core/Document.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ReamController.h"
#include "reamsim/tools/Primitives.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim {
namespace {

// The local cutting engine with the given contact engine.
struct Scene : test::ReamScene {
  Scene(const TriangleMesh& mesh, const ReamerSpec& spec, std::unique_ptr<ContactBackend> contact)
      : ReamScene(mesh, spec, localCutBackendFactory(), std::move(contact)) {}
};

TriangleMesh block() { return test::blockBelowZ0(); }
Pose at(double z) { return Pose{{0, 0, z}, {0, 0, -1}, 0}; }

TEST(BvhContact, SameCutsAsTheThesisRaysOnABlock) {
  Scene bvh(block(), test::flatReamer20(), makeBvhContactBackend());
  Scene thesis(block(), test::flatReamer20(), makeThesisContactBackend());
  for (double z : {2.0, 1.0, 0.4, -0.3, -0.8, -1.3}) {
    const ReamStepOutcome a = bvh.controller->moveTo(at(z));
    const ReamStepOutcome b = thesis.controller->moveTo(at(z));
    EXPECT_EQ(a.cut.changed, b.cut.changed) << "z " << z;
    EXPECT_NEAR(a.entry.removedMm3, b.entry.removedMm3, 1e-9) << "z " << z;
    if (z > 0) {
      // A flat face above a flat top: the true distance and the thesis's axial gap are both z (the thesis
      // measures only once the boxes overlap; the BVH engine always does).
      EXPECT_NEAR(a.contact.minDistanceMm, z, 1e-9) << "z " << z;
      if (b.contact.boxesOverlap) {
        EXPECT_NEAR(b.contact.minDistanceMm, z, 1e-9) << "z " << z;
      }
      EXPECT_FALSE(a.contact.penetrating);
      ASSERT_TRUE(a.contact.solidOverlapsBone.has_value());
      EXPECT_FALSE(*a.contact.solidOverlapsBone);
    } else {
      EXPECT_TRUE(a.contact.penetrating);
      EXPECT_EQ(a.contact.minDistanceMm, 0.0);
      EXPECT_NEAR(a.contact.penetrationDepthMm, -z, 1e-6) << "z " << z;
      EXPECT_GT(a.contact.touchedFaces, 0u);
    }
  }
  EXPECT_NEAR(bvh.bone->current().volume(), thesis.bone->current().volume(), 1e-6);
}

TEST(BvhContact, NoBooleanWhileTheReamerIsClear) {
  Scene bvh(block(), test::flatReamer20(), makeBvhContactBackend());
  Scene thesis(block(), test::flatReamer20(), makeThesisContactBackend());
  for (Scene* s : {&bvh, &thesis}) s->controller->moveTo(at(1.0));
  // 0.6 mm of travel: the grown boxes overlap, the solid does not reach the top (0.4 mm left).
  const ReamStepOutcome a = bvh.controller->moveTo(at(0.4));
  const ReamStepOutcome b = thesis.controller->moveTo(at(0.4));
  EXPECT_TRUE(a.contact.boxesOverlap);
  EXPECT_TRUE(b.contact.boxesOverlap);
  EXPECT_FALSE(a.cut.changed);
  EXPECT_FALSE(b.cut.changed);
  EXPECT_EQ(a.cut.milliseconds, 0.0) << "the BVH engine knows the solid is clear: no Boolean";
  EXPECT_GT(b.cut.milliseconds, 0.0) << "the thesis path runs the Boolean whenever the boxes overlap";
}

TEST(BvhContact, DistanceAfterBackingOffAReamedHoleIsTheGap) {
  Scene s(block(), test::flatReamer20(), makeBvhContactBackend());
  for (double z : {0.5, -0.5, -1.3}) s.controller->moveTo(at(z));
  ASSERT_GT(s.log->cumulativeMm3(), 300.0);
  // Backed off 1 mm above the top: the closest bone is the hole's rim, 1 mm below the face.
  const ReamStepOutcome out = s.controller->moveTo(at(1.0));
  EXPECT_FALSE(out.contact.penetrating);
  EXPECT_NEAR(out.contact.minDistanceMm, 1.0, 1e-9);
  ASSERT_TRUE(out.contact.contactPoint.has_value());
  EXPECT_NEAR(out.contact.contactPoint->z, 0.0, 1e-9);
}

TEST(BvhContact, DefaultPlanMatchesTheThesisPathWithSaneContacts) {
  const DefaultBone bone = loadDefaultBone();
  const ReamPlan plan = loadPlan(defaultPlanPath());
  const ReamerSpec spec = loadPreset(plan.reamer, reamerPresetsPath());
  Scene bvh(bone.mesh, spec, makeBvhContactBackend());
  Scene thesis(bone.mesh, spec, makeThesisContactBackend());
  const Bounds box = computeBounds(bone.mesh).expanded(1.0);
  std::size_t cuts = 0;
  for (const Pose& pose : plan.expandedPoses()) {
    const ReamStepOutcome a = bvh.controller->moveTo(pose);
    const ReamStepOutcome b = thesis.controller->moveTo(pose);
    EXPECT_NEAR(a.entry.removedMm3, b.entry.removedMm3, 1e-9 * std::max(1.0, b.entry.removedMm3));
    cuts += a.cut.changed;
    // The true face distance can only be shorter than the thesis's axial gap from the face vertices.
    if (std::isfinite(b.contact.minDistanceMm)) {
      EXPECT_LE(a.contact.minDistanceMm, b.contact.minDistanceMm + 1e-9);
    }
    ASSERT_TRUE(a.contact.contactPoint.has_value()) << "step " << a.entry.stepIndex;
    const Vec3 p = *a.contact.contactPoint;
    EXPECT_TRUE(box.overlaps(Bounds{p, p})) << "step " << a.entry.stepIndex;
    // The reamer never goes deeper than the plan's feed (25 x 0.2 mm) past the first contact.
    EXPECT_LE(a.contact.penetrationDepthMm, 5.0) << "step " << a.entry.stepIndex;
  }
  EXPECT_GE(cuts, 15u);
  EXPECT_NEAR(bvh.log->cumulativeMm3(), thesis.log->cumulativeMm3(), 1e-6);
}

}  // namespace
}  // namespace reamsim
