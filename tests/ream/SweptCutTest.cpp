// Swept cutting: a sideways translation cuts the whole volume the reamer sweeps (the hull of its two
// placements), so a long move leaves no ridge; axial feeds and turns cut the end pose's solid as before.
#include <gtest/gtest.h>

#include <algorithm>

#include "ReamFixture.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/csg/SweptVolume.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim {
namespace {

TriangleMesh block() { return test::blockBelowZ0(60); }
Pose at(double x, double z) { return Pose{{x, 0, z}, {0, 0, -1}, 0}; }

// Width of the reamer's cross-section across the direction of travel (x): what a sideways sweep removes per
// mm of travel and mm of depth.
double widthAcrossX(const TriangleMesh& solid) {
  double lo = 1e300, hi = -1e300;
  for (const Vec3& p : solid.vertices) {
    lo = std::min(lo, p.y);
    hi = std::max(hi, p.y);
  }
  return hi - lo;
}

class SweptCutEngines : public ::testing::TestWithParam<bool> {};  // local engine, or the CGAL reference

TEST_P(SweptCutEngines, SidewaysMoveRemovesTheSweptSlot) {
  test::ReamScene s(block(), test::flatReamer20(), GetParam() ? localCutBackendFactory() : referenceCutBackendFactory());
  const TriangleMesh solid = *s.reamer->cuttingVolume();
  ASSERT_TRUE(isConvexSolid(solid));
  s.controller->moveTo(at(-15, 1.0));                      // above the top
  const ReamStepOutcome down = s.controller->moveTo(at(-15, -1.0));  // 1 mm in: a disc
  EXPECT_FALSE(down.swept);                                 // axial: the end solid covers it
  const double disc = down.cut.removedMm3;
  EXPECT_GT(disc, 300.0);
  const ReamStepOutcome across = s.controller->moveTo(at(15, -1.0));  // 30 mm sideways in one step
  EXPECT_TRUE(across.swept);
  // The slot between the two discs: travel x width x depth (the end disc overlaps nothing cut before... it
  // does not: 30 mm > the 20 mm diameter, so the slot and the second disc are all new).
  EXPECT_NEAR(across.cut.removedMm3, 30.0 * widthAcrossX(solid) * 1.0, 1e-6 * across.cut.removedMm3);
  EXPECT_NEAR(s.log->cumulativeMm3(), disc + across.cut.removedMm3, 1e-6);
  EXPECT_FALSE(s.controller->checkBone().selfIntersectsExact);
}

INSTANTIATE_TEST_SUITE_P(SweptCut, SweptCutEngines, ::testing::Values(true, false),
                         [](const auto& info) { return info.param ? "local" : "reference"; });

TEST(SweptCut, WithoutMotionThePlacedSolidIsCut) {
  // The same end pose reached by placing the reamer: only the end disc goes, the ridge between stays.
  test::ReamScene s(block(), test::flatReamer20());
  s.controller->moveTo(at(-15, -1.0));
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), referenceCutBackendFactory());
  const ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(15, -1.0), 30.0);
  EXPECT_FALSE(c.swept);
  EXPECT_LT(c.cut.removedMm3, 0.6 * 30.0 * widthAcrossX(*s.reamer->cuttingVolume()));
}

TEST(SweptCut, AxialJumpLongerThanTheSolidIsSwept) {
  // The flat reamer is 10 mm long: a 15 mm plunge in one step would leave 5 mm uncut between the two solids.
  test::ReamScene s(block(), test::flatReamer20());
  s.controller->moveTo(at(0, 1.0));
  const ReamStepOutcome shortFeed = s.controller->moveTo(at(0, -2.0));  // 3 mm: covered, not swept
  EXPECT_FALSE(shortFeed.swept);
  const ReamStepOutcome plunge = s.controller->moveTo(at(0, -17.0));  // 15 mm at once
  EXPECT_TRUE(plunge.swept);
  const double disc = shortFeed.cut.removedMm3 / 2.0;  // per mm of depth
  EXPECT_NEAR(plunge.cut.removedMm3, 15.0 * disc, 1e-6 * plunge.cut.removedMm3);
}

TEST(SweptCut, TurnsAreNotSwept) {
  test::ReamScene s(block(), test::flatReamer20());
  s.controller->moveTo(at(0, -1.0));
  Pose tilted = at(5, -1.0);
  tilted.axis = normalized(Vec3{0.05, 0, -1});
  EXPECT_FALSE(s.controller->moveTo(tilted).swept);
}

TEST(SweptCut, HullOfTwoPlacementsIsClosedAndHasTheExpectedVolume) {
  const TriangleMesh solid = buildCuttingSolid(test::flatReamer20());
  const RigidTransform a = toTransform(at(0, 0)), b = toTransform(at(7, 0));
  const TriangleMesh hull = sweptByTranslation(solid, a, b);
  EXPECT_TRUE(isConvexSolid(hull));
  EXPECT_NEAR(signedVolume(hull), signedVolume(solid) + 7.0 * widthAcrossX(solid) * 10.0, 1e-6);
  RigidTransform turned = b;
  turned.rotation[0] = 0.5;
  EXPECT_THROW(sweptByTranslation(solid, a, turned), std::invalid_argument);
}

}  // namespace
}  // namespace reamsim
