// BoneCollider (the BVH kept with a BoneState) and the thesis's proximity alerts published in the document.
#include <gtest/gtest.h>

#include "CollisionFixtures.h"
#include "reamsim/collision/BoneCollider.h"
#include "reamsim/collision/CollisionAlerts.h"
#include "reamsim/core/AlertNode.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/ReamerNode.h"
#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/collision/RayTriangle.h"
#include "reamsim/tools/ReamerGeometry.h"

#include <limits>
#include <string>
#include <utility>
#include <vector>

using namespace reamsim;

namespace {
RigidTransform above(const Vec3& tip) {
  Pose p;
  p.tip = tip;
  p.axis = {0, 0, -1};
  return toTransform(p);
}
}  // namespace

TEST(collisionBoneCollider, StateAndMeshGiveTheSameAnswers) {
  const TriangleMesh mesh = test::defaultScapula();
  const BoneCollider fromMesh(mesh);
  const BoneCollider fromState(BoneState::fromMesh(mesh));
  EXPECT_TRUE(fromMesh.closed());
  EXPECT_TRUE(fromState.closed());
  EXPECT_FALSE(BoneCollider(test::bundledScapula()).closed());  // the dirty OpenSim mesh is open
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(false, 24, 6));
  std::mt19937_64 rng(3);
  for (int i = 0; i < 200; ++i) {
    const RigidTransform T = toTransform(test::poseNearSurface(mesh, rng, -1.5, 3, 20));
    EXPECT_EQ(fromMesh.overlap(reamer, T).touchedSlots.size(), fromState.overlap(reamer, T).touchedSlots.size());
    EXPECT_NEAR(fromMesh.faceDistance(reamer, T).distanceMm, fromState.faceDistance(reamer, T).distanceMm, 1e-12);
    EXPECT_NEAR(fromMesh.axialPenetration(reamer, T).depthMm, fromState.axialPenetration(reamer, T).depthMm, 1e-9);
  }
}

TEST(collisionAlerts, ThesisAlertsFromTheExactQueries) {
  Document doc;
  auto& bone = doc.create<BoneNode>("Bone");
  auto& reamerNode = doc.create<ReamerNode>("Reamer");
  auto& alerts = doc.create<AlertNode>("Alerts");
  // A slab (top face z = 20) and a tower beside it, so that the bone's box reaches above the slab.
  TriangleMesh bone2 = test::block({-30, -30, 0}, {30, 30, 20}, 4);
  const TriangleMesh tower = test::block({40, -10, 0}, {60, 10, 40}, 2);
  const std::uint32_t base = static_cast<std::uint32_t>(bone2.vertices.size());
  bone2.vertices.insert(bone2.vertices.end(), tower.vertices.begin(), tower.vertices.end());
  for (Triangle t : tower.triangles) bone2.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const BoneCollider collider(bone2);
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(true));   // flat 20 mm reamer, 6 mm body

  // Far away: nothing.
  ProximityStatus s = evaluateProximity(collider, reamer, above({0, 0, 60}));
  EXPECT_FALSE(s.boxesOverlap);
  publishProximity(alerts, s, reamerNode.id(), bone.id());
  EXPECT_TRUE(alerts.alerts().empty());

  // Hovering 1.25 mm above the slab, inside the bone's box: boxes overlap, no contact, the exact distance.
  s = evaluateProximity(collider, reamer, above({0, 0, 21.25}));
  EXPECT_TRUE(s.boxesOverlap);
  EXPECT_FALSE(s.contact);
  EXPECT_NEAR(s.distanceMm, 1.25, 1e-12);
  publishProximity(alerts, s, reamerNode.id(), bone.id());
  ASSERT_EQ(alerts.alerts().size(), 1u);
  EXPECT_TRUE(alerts.has(AlertKind::BoundsOverlap));
  EXPECT_NE(describe(alerts.alerts()[0]).find("bounding boxes overlap (distance 1.25 mm)"), std::string::npos);

  // Touching without penetrating, then pressed in: contact.
  for (double z : {20.0, 19.5}) {
    s = evaluateProximity(collider, reamer, above({0, 0, z}));
    EXPECT_TRUE(s.contact) << z;
    publishProximity(alerts, s, reamerNode.id(), bone.id());
    EXPECT_TRUE(alerts.has(AlertKind::Contact));
    EXPECT_TRUE(alerts.has(AlertKind::BoundsOverlap));
  }
  EXPECT_NE(describe(alerts.alerts()[1]).find("contact"), std::string::npos);
}

// The application hands the collision engine a reamer node's cutting volume and spec: the ideal solid (the
// fast path's bounds) is used only when the volume is exactly the spec's own mesh.
TEST(collisionReamerModel, CuttingVolumeUsesItsSpecOnlyWhenItIsTheSpecsMesh) {
  for (const bool flat : {false, true}) {
    const ReamerSpec spec = test::smallSpec(flat);
    const TriangleMesh own = buildCuttingSolid(spec);
    const ReamerModel model = ReamerModel::fromCuttingVolume(own, &spec);
    EXPECT_TRUE(model.idealSolid().valid) << flat;
    EXPECT_EQ(model.faceTriangles(), ReamerModel::fromSpec(spec).faceTriangles()) << flat;
    EXPECT_FALSE(ReamerModel::fromCuttingVolume(own, nullptr).idealSolid().valid) << flat;
    TriangleMesh moved = own;
    moved.vertices[moved.vertices.size() / 2].z += 1e-9;  // no longer inscribed as the spec says
    EXPECT_FALSE(ReamerModel::fromCuttingVolume(moved, &spec).idealSolid().valid) << flat;
    ReamerSpec other = spec;
    other.segments += 4;  // the same shape at another resolution: a different mesh
    EXPECT_FALSE(ReamerModel::fromCuttingVolume(own, &other).idealSolid().valid) << flat;
    ReamerSpec fromFile = spec;
    fromFile.meshFile = "cutter.stl";
    EXPECT_FALSE(ReamerModel::fromCuttingVolume(own, &fromFile).idealSolid().valid) << flat;
  }
}

// The inside test (ideal-solid shortcut, pseudo-normal search in the band) against crossing parity, away
// from the surface where parity is reliable; for spherical, flat and mesh-file reamers.
TEST(collisionReamerModel, InsideTestAgreesWithCrossingParity) {
  ReamerSpec fine = test::smallSpec(false, 96, 12);
  fine.diameterMm = 36;
  fine.sphereRadiusMm = 30;
  const ReamerModel models[] = {ReamerModel::fromSpec(test::smallSpec(false)), ReamerModel::fromSpec(test::smallSpec(true)),
                                ReamerModel::fromSpec(fine), ReamerModel::fromSolid(buildCuttingSolid(fine))};
  EXPECT_TRUE(models[0].idealSolid().valid);
  EXPECT_TRUE(models[1].idealSolid().valid);
  EXPECT_FALSE(models[3].idealSolid().valid);  // a mesh from a file: search only
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 dir{0.2672612419124244, 0.5345224838248488, 0.8017837257372732};
  for (const ReamerModel& m : models) {
    const Bounds b = computeBounds(m.solid()).expanded(2);
    std::size_t inside = 0, checked = 0;
    for (int i = 0; i < 5000; ++i) {
      const Vec3 p{b.min.x + u(rng) * (b.max.x - b.min.x), b.min.y + u(rng) * (b.max.y - b.min.y),
                   b.min.z + u(rng) * (b.max.z - b.min.z)};
      if (norm(p - m.closestSurfacePoint(p)) < 1e-6) continue;
      const bool parity = allHits(m.solid(), p, dir).size() % 2 == 1;
      EXPECT_EQ(m.containsLocal(p), parity) << p.x << " " << p.y << " " << p.z;
      inside += parity;
      ++checked;
    }
    EXPECT_GT(inside, checked / 10);
  }
  // Points just inside and outside the facets (within the sag band) go through the exact search.
  const ReamerModel& m = models[2];
  for (const Triangle& t : m.solid().triangles) {
    const Vec3 c = (m.solid().vertices[t[0]] + m.solid().vertices[t[1]] + m.solid().vertices[t[2]]) / 3.0;
    const Vec3 n = normalized(cross(m.solid().vertices[t[1]] - m.solid().vertices[t[0]], m.solid().vertices[t[2]] - m.solid().vertices[t[0]]));
    EXPECT_TRUE(m.containsLocal(c - n * 1e-7));
    EXPECT_FALSE(m.containsLocal(c + n * 1e-7));
  }
}

// A pose with a NaN or an infinity, or a rotation that is not one, has no answer: every pose query refuses it
// naming itself and the pose, rather than answering "no contact" (which would let a reamer driven by a
// faulty device pass through the bone).
TEST(collisionBoneCollider, QueriesRefuseNonFiniteOrNonRigidPoses) {
  const BoneCollider bone(test::defaultScapula());
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(false, 24, 6));
  const RigidTransform good = above({0, 0, 5000});  // far from the bone
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<RigidTransform> bad(4, good);
  bad[0].translation.y = nan;
  bad[1].rotation[4] = nan;
  bad[2].translation.z = -inf;
  bad[3].rotation[0] = 2.0;  // a scaling, not a rotation
  for (const RigidTransform& p : bad) {
    EXPECT_THROW(bone.overlap(reamer, p), std::invalid_argument);
    EXPECT_THROW(bone.overlap(reamer, p, OverlapMode::AnyContact), std::invalid_argument);
    EXPECT_THROW(bone.faceDistance(reamer, p), std::invalid_argument);
    EXPECT_THROW(bone.firstContact(reamer, p, good), std::invalid_argument);
    EXPECT_THROW(bone.firstContact(reamer, good, p), std::invalid_argument);
    EXPECT_THROW(bone.axialPenetration(reamer, p), std::invalid_argument);
    EXPECT_THROW(FaceDistanceTracker().query(bone.bvh(), reamer, p), std::invalid_argument);
  }
  try {
    bone.firstContact(reamer, good, bad[0]);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("queryFirstContact"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("end pose"), std::string::npos) << e.what();
  }
  // The good pose still answers.
  EXPECT_FALSE(bone.firstContact(reamer, good, good).hit);
  EXPECT_NO_THROW(bone.faceDistance(reamer, good));
}

// Rays likewise (query 4, the tree's and the thesis's brute force alike): a NaN origin made every triangle a
// "hit" at t = NaN before (Moeller-Trumbore's tests passed NaNs), a zero direction answered "no hit".
TEST(collisionBoneCollider, RaysRefuseNonFiniteOriginsAndDirections) {
  const TriangleMesh mesh = test::defaultScapula();
  const BoneCollider bone(mesh);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::pair<Vec3, Vec3> bad[] = {{{0, nan, 0}, {0, 0, 1}}, {{0, 0, 0}, {0, 0, inf}}, {{0, 0, 0}, {nan, 0, 1}},
                                       {{0, 0, -inf}, {0, 0, 1}}, {{0, 0, 0}, {0, 0, 0}}};
  for (const auto& [o, d] : bad) {
    EXPECT_THROW(bone.firstHit(o, d), std::invalid_argument);
    EXPECT_THROW(bone.allHits(o, d, Culling::BackFaces), std::invalid_argument);
    EXPECT_THROW(firstHit(mesh, o, d), std::invalid_argument);
    EXPECT_THROW(allHits(mesh, o, d), std::invalid_argument);
  }
  // The per-triangle test itself answers no hit to a NaN ray.
  EXPECT_FALSE(intersectRayTriangle({0.2, nan, 1}, {0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}).has_value());
  EXPECT_TRUE(intersectRayTriangle({0.2, 0.2, 1}, {0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}).has_value());
  try {
    bone.allHits({0, nan, 0}, {0, 0, 1});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("allHits"), std::string::npos) << e.what();
  }
}
