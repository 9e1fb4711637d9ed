#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "TestMeshes.h"
#include "reamsim/collision/BroadPhase.h"
#include "reamsim/collision/ThesisContact.h"
#include "reamsim/tools/ReamerGeometry.h"

using namespace reamsim;

namespace {
// Bone: a slab whose front face is the plane z = 10, much wider than the reamer.
const TriangleMesh kBone = test::makeBox({-50, -50, 10}, {50, 50, 40});
const Bounds kBoneBounds = computeBounds(kBone);
const Vec3 kFeed{0, 0, 1};

ReamerSpec flatReamer() {
  ReamerSpec s;
  s.name = "flat-30";
  s.diameterMm = 30;
  s.bodyLengthMm = 10;
  s.segments = 32;
  s.rings = 4;
  return s;
}
ReamerSpec sphericalReamer() {
  ReamerSpec s = flatReamer();
  s.name = "glenoid-40-R32";
  s.diameterMm = 40;
  s.sphereRadiusMm = 32;
  return s;
}

// Reamer placed with its tip at `tip`, feeding along +Z (identity rotation, so no core transform needed).
struct Placed {
  TriangleMesh solid;
  std::vector<Vec3> face;
};
Placed place(const ReamerSpec& s, const Vec3& tip) {
  Placed p{buildCuttingSolid(s), cuttingFaceVertices(s)};
  for (Vec3& v : p.solid.vertices) v += tip;
  for (Vec3& v : p.face) v += tip;
  return p;
}
ContactResult query(const ReamerSpec& s, double tipZ, double step) {
  const Placed p = place(s, {0, 0, tipZ});
  return thesisContactQuery(kBone, kBoneBounds, p.solid, p.face, kFeed, step);
}
}  // namespace

TEST(collisionBroadPhase, ClosedIntervals) {
  Bounds a, b, empty;
  a.add({0, 0, 0});
  a.add({1, 1, 1});
  b.add({1, 0, 0});
  b.add({2, 1, 1});
  EXPECT_TRUE(boundsOverlap(a, b));  // touching faces overlap
  EXPECT_FALSE(boundsOverlap(a, b.expanded(-0.5)));
  EXPECT_FALSE(boundsOverlap(a, empty));
}

TEST(collisionThesisContact, GapIsExact) {
  const ContactResult r = query(flatReamer(), 7.5, 5.0);
  EXPECT_TRUE(r.boxesOverlap);
  EXPECT_FALSE(r.penetrating);
  EXPECT_TRUE(r.contact);  // 2.5 <= 5
  EXPECT_NEAR(r.minDistanceMm, 2.5, 1e-9);
  EXPECT_EQ(r.penetrationDepthMm, 0.0);
  ASSERT_TRUE(r.contactPoint);
  EXPECT_NEAR(r.contactPoint->z, 10.0, 1e-9);
  EXPECT_EQ(r.raysCast, cuttingFaceVertices(flatReamer()).size());

  const ContactResult s = query(sphericalReamer(), 6.25, 5.0);
  EXPECT_NEAR(s.minDistanceMm, 3.75, 1e-9);  // the apex is the closest point of a convex face
  ASSERT_TRUE(s.contactPoint);
  EXPECT_NEAR(norm(*s.contactPoint - Vec3(0, 0, 10)), 0.0, 1e-9);
}

TEST(collisionThesisContact, BroadPhaseRejectsFarReamer) {
  const ContactResult r = query(flatReamer(), 7.5, 1.0);  // reamer box grown by 1 ends at z = 8.5
  EXPECT_FALSE(r.boxesOverlap);
  EXPECT_FALSE(r.contact);
  EXPECT_EQ(r.raysCast, 0u);
  EXPECT_TRUE(std::isinf(r.minDistanceMm));
}

TEST(collisionThesisContact, ContactFlipsAtTheRightStep) {
  // Feed from z = 0 in 0.75 mm steps; the face reaches within one step of z = 10 at step 13 (gap 0.25).
  const double step = 0.75;
  int firstContact = -1;
  for (int k = 0; k <= 20 && firstContact < 0; ++k) {
    const ContactResult r = query(flatReamer(), k * step, step);
    if (r.contact) {
      firstContact = k;
      EXPECT_NEAR(r.minDistanceMm, 10 - k * step, 1e-9);
    }
  }
  EXPECT_EQ(firstContact, 13);
  // Gap exactly equal to the step counts as contact.
  const ContactResult atStep = query(flatReamer(), 9.0, 1.0);
  EXPECT_TRUE(atStep.contact);
  EXPECT_NEAR(atStep.minDistanceMm, 1.0, 1e-9);
  EXPECT_FALSE(query(flatReamer(), 9.0, 0.5).contact);
}

TEST(collisionThesisContact, TouchingIsContactWithoutPenetration) {
  const ContactResult r = query(flatReamer(), 10.0, 0.5);
  EXPECT_TRUE(r.contact);
  EXPECT_FALSE(r.penetrating);
  EXPECT_EQ(r.minDistanceMm, 0.0);
}

TEST(collisionThesisContact, PenetrationDepth) {
  const std::size_t faceVertices = cuttingFaceVertices(flatReamer()).size();
  const ContactResult r = query(flatReamer(), 13.0, 0.5);
  EXPECT_TRUE(r.contact);
  EXPECT_TRUE(r.penetrating);
  EXPECT_EQ(r.minDistanceMm, 0.0);
  EXPECT_NEAR(r.penetrationDepthMm, 3.0, 1e-9);
  EXPECT_EQ(r.insideVertices, faceVertices);
  EXPECT_EQ(r.raysCast, 2 * faceVertices);  // forward parity ray + backward depth ray each
  ASSERT_TRUE(r.contactPoint);
  EXPECT_NEAR(r.contactPoint->z, 10.0, 1e-9);

  // Spherical face: only the vertices ahead of the bone surface are inside; the apex is deepest.
  const ReamerSpec sph = sphericalReamer();
  const ContactResult s = query(sph, 12.0, 0.5);
  EXPECT_TRUE(s.penetrating);
  EXPECT_NEAR(s.penetrationDepthMm, 2.0, 1e-9);
  EXPECT_GT(s.insideVertices, 0u);
  EXPECT_LT(s.insideVertices, cuttingFaceVertices(sph).size());
  ASSERT_TRUE(s.contactPoint);
  EXPECT_NEAR(norm(*s.contactPoint - Vec3(0, 0, 10)), 0.0, 1e-9);
}

TEST(collisionThesisContact, OtherFeedAxis) {
  // Feed along -X into a bone whose front face is x = -10: local (x, y, z) -> (-z, y, x) + tip.
  const TriangleMesh bone = test::makeBox({-40, -50, -50}, {-10, 50, 50});
  Placed p = place(flatReamer(), {0, 0, 0});
  const Vec3 tip{-8, 1, 2};
  auto toBone = [&](Vec3& v) { v = Vec3{-v.z, v.y, v.x} + tip; };
  for (Vec3& v : p.solid.vertices) toBone(v);
  for (Vec3& v : p.face) toBone(v);
  ASSERT_GT(signedVolume(p.solid), 0);  // still a proper rotation
  const ContactResult r = thesisContactQuery(bone, computeBounds(bone), p.solid, p.face, {-2, 0, 0}, 3.0);
  EXPECT_TRUE(r.contact);
  EXPECT_NEAR(r.minDistanceMm, 2.0, 1e-9);
}

TEST(collisionThesisContact, RaysThatMissTheBoneGiveNoContact) {
  // Boxes overlap (the bone is beside the reamer), but no ray along +Z meets it.
  const TriangleMesh bone = test::makeBox({15.5, -5, -20}, {30, 5, 20});
  const Placed p = place(flatReamer(), {0, 0, 0});
  const ContactResult r = thesisContactQuery(bone, computeBounds(bone), p.solid, p.face, kFeed, 1.0);
  EXPECT_TRUE(r.boxesOverlap);
  EXPECT_FALSE(r.contact);
  EXPECT_TRUE(std::isinf(r.minDistanceMm));
  EXPECT_FALSE(r.contactPoint);
  EXPECT_GT(r.raysCast, 0u);
}

TEST(collisionThesisContact, RejectsBadArguments) {
  const Placed p = place(flatReamer(), {0, 0, 0});
  EXPECT_THROW(thesisContactQuery(kBone, kBoneBounds, p.solid, p.face, {0, 0, 0}, 1.0), std::invalid_argument);
  EXPECT_THROW(thesisContactQuery(kBone, kBoneBounds, p.solid, p.face, kFeed, -1.0), std::invalid_argument);
}
