// Queries 1 and 2 against their brute-force references (every triangle pair): >= 10,000 random poses per
// query over three bones and two reamers, plus the degenerate configurations (touching without
// penetration, coplanar and parallel faces). Tolerances: touched sets identical; distances within
// 1e-9 x (1 + d) mm.
#include <gtest/gtest.h>

#include <random>

#include "CollisionFixtures.h"
#include "PropertyBones.h"
#include "reamsim/collision/BruteForce.h"
#include "reamsim/collision/DistanceQuery.h"
#include "reamsim/collision/OverlapQuery.h"
#include "reamsim/collision/TriangleGeometry.h"

using namespace reamsim;
using namespace reamsim::test;  // the shared property-test bones (PropertyBones.h)

namespace {

struct Counts {
  std::size_t queries = 0, overlapping = 0, withInsideFaces = 0, touching = 0;
};

Counts checkOverlap(const TriangleMesh& bone, bool closed, std::size_t n, std::uint64_t seed) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  const ReamerModel reamers[2] = {ReamerModel::fromSpec(test::smallSpec(false)), ReamerModel::fromSpec(test::smallSpec(true))};
  std::mt19937_64 rng(seed);
  Counts c;
  for (std::size_t i = 0; i < n; ++i) {
    const ReamerModel& reamer = reamers[i % 2];
    const RigidTransform T = toTransform(test::poseNearSurface(bone, rng, -4, 3, 30));
    const OverlapResult ref = bruteForceOverlap(bone, reamer, T, closed);
    const OverlapResult all = queryOverlap(bvh, reamer, T, OverlapMode::AllTouchedFaces, closed);
    const OverlapResult any = queryOverlap(bvh, reamer, T, OverlapMode::AnyContact, closed);
    EXPECT_EQ(all.touchedSlots, ref.touchedSlots) << "query " << i;
    EXPECT_EQ(all.surfaceCrossings, ref.surfaceCrossings);
    EXPECT_EQ(all.insideFaces, ref.insideFaces);
    EXPECT_EQ(all.overlap, ref.overlap);
    EXPECT_EQ(all.reamerInsideBone, ref.reamerInsideBone);
    EXPECT_EQ(any.overlap, ref.overlap);
    EXPECT_LE(any.touchedSlots.size(), 1u);
    if (::testing::Test::HasFailure()) return c;
    ++c.queries;
    c.overlapping += ref.overlap;
    c.withInsideFaces += ref.insideFaces > 0;
  }
  return c;
}

// Distance of p to triangle `slot` of m.
double toTriangle(const TriangleMesh& m, std::size_t slot, const Vec3& p) {
  const Triangle& t = m.triangles[slot];
  return norm(p - closestPointOnTriangle(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
}

Counts checkDistance(const TriangleMesh& bone, std::size_t n, std::uint64_t seed) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  const ReamerModel reamers[2] = {ReamerModel::fromSpec(test::smallSpec(false)), ReamerModel::fromSpec(test::smallSpec(true))};
  std::mt19937_64 rng(seed);
  Counts c;
  for (std::size_t i = 0; i < n; ++i) {
    const ReamerModel& reamer = reamers[i % 2];
    const RigidTransform T = toTransform(test::poseNearSurface(bone, rng, -1, 5, 30));
    const DistanceResult ref = bruteForceFaceDistance(bone, reamer, T);
    const DistanceResult got = queryFaceDistance(bvh, reamer, T);
    EXPECT_TRUE(ref.found && got.found);
    if (!ref.found || !got.found) return c;
    EXPECT_NEAR(got.distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << "query " << i;
    // The pair is a real pair at that distance: on the reported bone triangle and on the posed face triangle.
    EXPECT_NEAR(norm(got.onReamer - got.onBone), got.distanceMm, 1e-9 * (1 + got.distanceMm));
    EXPECT_LE(toTriangle(bone, got.boneSlot, got.onBone), 1e-9);
    TriangleMesh posed = reamer.solid();
    for (Vec3& v : posed.vertices) v = T.apply(v);
    EXPECT_LE(toTriangle(posed, got.reamerTriangle, got.onReamer), 1e-9);
    // Within a maximum distance: found exactly when the true distance is within it.
    const DistanceResult capped = queryFaceDistance(bvh, reamer, T, 2.0);
    EXPECT_EQ(capped.found, ref.distanceMm <= 2.0);
    if (::testing::Test::HasFailure()) return c;
    ++c.queries;
    c.touching += ref.distanceMm == 0;
  }
  return c;
}

}  // namespace

TEST(collisionOverlapProperty, SphereClosed) {
  const Counts c = checkOverlap(sphere(), true, kSphereQueries, 11);
  EXPECT_EQ(c.queries, kSphereQueries);
  EXPECT_GT(c.overlapping, 1000u);
  EXPECT_GT(c.withInsideFaces, 100u);
}
TEST(collisionOverlapProperty, SlabClosed) {
  const Counts c = checkOverlap(slab(), true, kSlabQueries, 12);
  EXPECT_EQ(c.queries, kSlabQueries);
  EXPECT_GT(c.overlapping, 1000u);
}
TEST(collisionOverlapProperty, BundledScapulaOpen) {
  const Counts c = checkOverlap(scapula(), false, kScapulaQueries, 13);
  EXPECT_EQ(c.queries, kScapulaQueries);
  EXPECT_GT(c.overlapping, 1000u);
}

TEST(collisionDistanceProperty, Sphere) { EXPECT_EQ(checkDistance(sphere(), kSphereQueries, 21).queries, kSphereQueries); }
TEST(collisionDistanceProperty, Slab) { EXPECT_EQ(checkDistance(slab(), kSlabQueries, 22).queries, kSlabQueries); }
TEST(collisionDistanceProperty, BundledScapula) {
  const Counts c = checkDistance(scapula(), kScapulaQueries, 23);
  EXPECT_EQ(c.queries, kScapulaQueries);
  EXPECT_GT(c.touching, 100u);
}

// The reamer seated in a concave bone, where every bone face is nearly as far from the cap as the nearest:
// the distance search's node bounds (box and slab) are tested where they decide the most. The cap (sphere
// radius 16) turns about the centre of a 17 mm spherical cavity, its centre up to 0.9 mm off; the flat
// reamer hovers over the slab's top within 2 degrees of parallel.
TEST(collisionDistanceProperty, ReamerSeatedInAConcaveBone) {
  const ParallelBones bones(4);
  const Vec3& o = bones.centre;
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> u(-1, 1);
  auto unit = [&] { return randomUnit(rng); };
  for (int i = 0; i < 600; ++i) {
    const bool seated = i % 2 == 0;
    Pose p;
    if (seated) {  // sphere centre = tip - 16 axis
      p.axis = unit();
      p.tip = o + unit() * (0.9 * std::abs(u(rng))) + p.axis * 16;
    } else {
      p.axis = normalized(Vec3{0, 0, -1} + unit() * std::tan(2 * 3.14159265358979 / 180 * std::abs(u(rng))));
      p.tip = {8 * u(rng), 8 * u(rng), 20 + 0.4 + 1.6 * std::abs(u(rng))};  // the rim tilts by <= 0.35 mm
    }
    p.rollDeg = 180 * u(rng);
    const RigidTransform T = toTransform(p);
    const TriangleMesh& bone = seated ? bones.cavity : slab();
    const ReamerModel& reamer = seated ? bones.round : bones.flat;
    const DistanceResult ref = bruteForceFaceDistance(bone, reamer, T);
    const DistanceResult got = queryFaceDistance(seated ? bones.cavityBvh : bones.slabBvh, reamer, T);
    ASSERT_TRUE(ref.found && got.found);
    EXPECT_GT(ref.distanceMm, 0) << "query " << i;  // apart: the nearest search decides, not the crossing
    EXPECT_NEAR(got.distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << "query " << i;
    EXPECT_NEAR(norm(got.onReamer - got.onBone), got.distanceMm, 1e-9 * (1 + got.distanceMm));
    if (::testing::Test::HasFailure()) return;
  }
}

// Bone beside the face's rim, nearly parallel to the face and a little in front of it: the nearest pair
// lies across the rim, so the distance query's bound across the bone triangle's plane (its plane gap and
// the separation along a direction in that plane) is tight there, and a bound that overshoots drops the
// nearest pair. Two triangles 0.2-2 mm across, 0.005-1 mm beyond the rim and in front of the rim's plane,
// tilted up to 10 degrees.
TEST(collisionDistanceProperty, BoneBesideTheRim) {
  const ParallelBones bones(1);
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> u(0, 1);
  const RigidTransform T = toTransform(Pose{});  // the reamer's own frame: face towards +z, apex at 0
  for (const ReamerModel* reamer : {&bones.flat, &bones.round}) {
    const double rimZ = reamer->idealSolid().capBaseZ;
    const double rimR = reamer->idealSolid().radius;
    for (int i = 0; i < 400; ++i) {
      const double phi = 2 * 3.14159265358979 * u(rng), size = 0.2 + 1.8 * u(rng);
      const double beyond = 0.005 + u(rng), front = 0.005 + u(rng), tilt = 0.17 * (2 * u(rng) - 1);
      const Vec3 out{std::cos(phi), std::sin(phi), 0}, side{-std::sin(phi), std::cos(phi), 0};
      const Vec3 up = normalized(Vec3{0, 0, 1} + out * tilt);
      const Vec3 across = normalized(out - up * dot(out, up));
      const Vec3 inner = out * (rimR + beyond) + Vec3{0, 0, rimZ + front} + side * (size * (u(rng) - 0.5));
      TriangleMesh bone;
      bone.vertices = {inner, inner + across * size, inner + across * size + side * size, inner + side * size};
      bone.triangles = {{0, 1, 2}, {0, 2, 3}};
      const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
      const DistanceResult ref = bruteForceFaceDistance(bone, *reamer, T);
      const DistanceResult got = queryFaceDistance(bvh, *reamer, T);
      ASSERT_TRUE(ref.found && got.found);
      EXPECT_GT(ref.distanceMm, 0) << "query " << i;
      EXPECT_NEAR(got.distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << "query " << i;
      if (::testing::Test::HasFailure()) return;
    }
  }
}

// Touching without penetration, coplanar faces, parallel faces at a known gap.
TEST(collisionOverlapProperty, DegenerateConfigurationsOnTheSlab) {
  const TriangleMesh& bone = slab();  // top face z = 20, grid vertices every 10 mm
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  const ReamerModel flat = ReamerModel::fromSpec(test::smallSpec(true));
  const ReamerModel round = ReamerModel::fromSpec(test::smallSpec(false));
  auto above = [](const Vec3& tip) {
    Pose p;
    p.tip = tip;
    p.axis = {0, 0, -1};
    return toTransform(p);
  };
  for (const ReamerModel* r : {&flat, &round})
    for (const Vec3& xy : {Vec3{0, 0, 0}, Vec3{10, 0, 0}, Vec3{5, 5, 0}, Vec3{3.3, 1.7, 0}})
      for (double gap : {0.0, 1e-13, 1e-9, 0.5, -0.5}) {
        const RigidTransform T = above(xy + Vec3{0, 0, 20 + gap});
        const OverlapResult ref = bruteForceOverlap(bone, *r, T, true);
        const OverlapResult got = queryOverlap(bvh, *r, T, OverlapMode::AllTouchedFaces, true);
        EXPECT_EQ(got.touchedSlots, ref.touchedSlots) << "gap " << gap;
        // Touching (within the 1e-12 relative tolerance) counts; a 1e-9 mm gap does not.
        EXPECT_EQ(got.overlap, gap < 1e-10) << "gap " << gap << " flat " << (r == &flat) << " x " << xy.x << " y " << xy.y << " crossings " << got.surfaceCrossings << " inside " << got.insideFaces;
        const DistanceResult d = queryFaceDistance(bvh, *r, T);
        const DistanceResult dref = bruteForceFaceDistance(bone, *r, T);
        EXPECT_NEAR(d.distanceMm, dref.distanceMm, 1e-12);
        if (gap >= 0) {
          EXPECT_NEAR(d.distanceMm, gap, 1e-12) << "gap " << gap;
        }
        // Pressed 0.5 mm in: the convex face crosses the surface (0); the flat face lies under it (0.5).
        if (gap < 0) {
          EXPECT_NEAR(d.distanceMm, r == &flat ? 0.5 : 0.0, 1e-12);
        }
      }
}

TEST(collisionOverlapProperty, ReamerEnclosedInClosedBoneOverlapsWithoutTouchedFaces) {
  const TriangleMesh bone = test::icosphere(3, 60, {0, 0, 0});
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  const ReamerModel r = ReamerModel::fromSpec(test::smallSpec(false));
  const RigidTransform inside = toTransform(Pose{{0, 0, 5}, {0, 0, 1}, 0});
  const OverlapResult got = queryOverlap(bvh, r, inside, OverlapMode::AllTouchedFaces, true);
  EXPECT_TRUE(got.overlap);
  EXPECT_TRUE(got.reamerInsideBone);
  EXPECT_TRUE(got.touchedSlots.empty());
  // The same bone treated as open has no volume: no overlap.
  EXPECT_FALSE(queryOverlap(bvh, r, inside, OverlapMode::AllTouchedFaces, false).overlap);
}

TEST(collisionOverlapProperty, BoneInsideTheReamerIsTouchedAsInsideFaces) {
  const TriangleMesh bone = test::icosphere(2, 2, {0, 0, -3});  // a 2 mm ball inside the body of the reamer (z in [-6, 0])
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  const ReamerModel r = ReamerModel::fromSpec(test::smallSpec(true));
  const OverlapResult got = queryOverlap(bvh, r, RigidTransform{}, OverlapMode::AllTouchedFaces, true);
  EXPECT_EQ(got.insideFaces, bone.triangles.size());
  EXPECT_EQ(got.surfaceCrossings, 0u);
  EXPECT_EQ(got.touchedSlots, bruteForceOverlap(bone, r, RigidTransform{}, true).touchedSlots);
}
