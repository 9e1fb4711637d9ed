// "Ream to depth" measures the depth from the first contact: how far the reamer can advance along its axis
// (exact first contact on the BVH) and the feed poses from there.
#include <gtest/gtest.h>

#include "ReamFixture.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/tools/Primitives.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {
namespace {

TEST(Approach, DistanceToTheFirstContactAlongTheAxis) {
  const BoneState block = BoneState::fromMesh(test::blockBelowZ0());
  const TriangleMesh tool = buildCuttingSolid(test::flatReamer20());
  const auto down = [](double z) { return Pose{{3, -2, z}, {0, 0, -1}, 0}; };
  EXPECT_NEAR(*advanceToContactMm(block, tool, down(2.0), 100), 2.0, 1e-9);
  EXPECT_NEAR(*advanceToContactMm(block, tool, down(37.25), 100), 37.25, 1e-9);
  EXPECT_EQ(*advanceToContactMm(block, tool, down(0.0), 100), 0.0);   // touching
  EXPECT_EQ(*advanceToContactMm(block, tool, down(-1.0), 100), 0.0);  // already inside
  EXPECT_FALSE(advanceToContactMm(block, tool, down(150.0), 100).has_value());  // out of reach
  EXPECT_FALSE(advanceToContactMm(block, tool, Pose{{0, 0, 15}, {0, 0, 1}, 0}, 100).has_value());  // away (body behind the tip clear)
  // Tilted 30 degrees: the rim reaches the top first, at z = 10 sin(30) = 5 above the tip's contact.
  const Vec3 axis = normalized(Vec3{std::sin(M_PI / 6), 0, -std::cos(M_PI / 6)});
  const double start = 20;  // tip height
  const double rimDrop = 10 * std::sin(M_PI / 6);
  const double expected = (start - rimDrop) / std::cos(M_PI / 6);
  EXPECT_NEAR(*advanceToContactMm(block, tool, Pose{{0, 0, start}, axis, 0}, 100), expected, 1e-6);
}

// With the spec the cutting volume was built from, the search runs on the reamer's ideal solid (the GUI's
// path): the same distances.
TEST(Approach, TheSpecsFastPathFindsTheSameContact) {
  const BoneState block = BoneState::fromMesh(test::blockBelowZ0());
  ReamerSpec glenoid = test::flatReamer20();
  glenoid.name = "spherical-36-R30";
  glenoid.diameterMm = 36;
  glenoid.sphereRadiusMm = 30;
  glenoid.rings = 8;
  for (const ReamerSpec& spec : {test::flatReamer20(), glenoid}) {
    const TriangleMesh tool = buildCuttingSolid(spec);
    for (const double z : {0.0, 2.0, 37.25}) {
      for (const double tilt : {0.0, 0.4}) {
        const Pose start{{3, -2, z}, normalized(Vec3{std::sin(tilt), 0, -std::cos(tilt)}), 0};
        const auto general = advanceToContactMm(block, tool, start, 100);
        const auto fast = advanceToContactMm(block, tool, start, 100, &spec);
        ASSERT_TRUE(general.has_value() && fast.has_value()) << spec.name << " " << z << " " << tilt;
        EXPECT_NEAR(*fast, *general, 1e-9) << spec.name << " " << z << " " << tilt;
      }
    }
  }
}

TEST(Approach, PosesMoveToContactThenFeedInSteps) {
  const Pose start{{0, 0, 10}, {0, 0, -1}, 0};
  const std::vector<Pose> p = reamToDepthPoses(start, 2.0, 1.0, 0.4);
  ASSERT_EQ(p.size(), 4u);
  const double z[] = {8.0, 7.6, 7.2, 7.0};
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p[i].tip.z, z[i], 1e-12) << i;
  EXPECT_EQ(reamToDepthPoses(start, 0.0, 1.0, 0.5).size(), 2u);  // touching: no approach move
  EXPECT_TRUE(reamToDepthPoses(start, -1.0, 1.0, 0.5).empty());
  EXPECT_TRUE(reamToDepthPoses(start, 1.0, 0.0, 0.5).empty());
}

}  // namespace
}  // namespace reamsim
