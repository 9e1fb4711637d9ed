// Queries 3 (first contact along a motion) and 5 (penetration depth along the axis) against their
// brute-force references, >= 10,000 random motions/poses each over three bones and two reamers, plus
// independent checks that do not share the event solver: at the reported time the surfaces touch and just
// before they do not; backed out by the reported depth they separate. Tolerance: 1e-9 in t, 1e-9 x reamer
// radius in depth.
#include <gtest/gtest.h>

#include <random>

#include "CollisionFixtures.h"
#include "PropertyBones.h"
#include "TestMeshes.h"
#include "reamsim/collision/BruteForce.h"
#include "reamsim/collision/FirstContact.h"
#include "reamsim/collision/PenetrationQuery.h"
#include "reamsim/collision/TriangleGeometry.h"
#include "reamsim/tools/ReamerGeometry.h"

using namespace reamsim;
using namespace reamsim::test;  // the shared property-test bones (PropertyBones.h)

namespace {

const double kPi = 3.14159265358979323846;

// Brute force over all pairs: do the posed reamer surface and the bone surface touch?
bool surfacesTouch(const TriangleMesh& bone, const ReamerModel& reamer, const RigidTransform& T) {
  TriangleMesh r = reamer.solid();
  for (Vec3& v : r.vertices) v = T.apply(v);
  const Bounds rb = computeBounds(r).expanded(1e-6);
  for (const Triangle& b : bone.triangles) {
    Bounds bb;
    for (std::uint32_t v : b) bb.add(bone.vertices[v]);
    if (!bb.overlaps(rb)) continue;
    for (const Triangle& t : r.triangles)
      if (trianglesIntersect(r.vertices[t[0]], r.vertices[t[1]], r.vertices[t[2]], bone.vertices[b[0]],
                             bone.vertices[b[1]], bone.vertices[b[2]]))
        return true;
  }
  return false;
}

// A motion that starts off the surface and heads towards it, with a lateral drift and a rotation; every
// fifth starts at or in the bone (the touch at the start).
std::pair<RigidTransform, RigidTransform> randomMotion(const TriangleMesh& bone, std::mt19937_64& rng, std::size_t i) {
  std::uniform_real_distribution<double> u(0, 1);
  const Pose start = i % 5 == 4 ? test::poseNearSurface(bone, rng, -1, 0.3, 30) : test::poseNearSurface(bone, rng, 0.3, 3, 30);
  const Vec3 lateral = anyPerpendicular(start.axis) * (u(rng) - 0.5);
  const Vec3 tip1 = start.tip + start.axis * (5 * u(rng) - 0.5) + lateral;
  const Vec3 k = normalized(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
  // Mostly small turns; every 50th motion turns by more than 90 degrees (several path segments).
  const double angle = (i % 50 == 0 ? 100 + 60 * u(rng) : 10 * u(rng)) * kPi / 180;
  const RigidTransform from = toTransform(start);
  RigidTransform to = from;
  to.translation = tip1;
  const Vec3 cols[3] = {{from.rotation[0], from.rotation[3], from.rotation[6]},
                        {from.rotation[1], from.rotation[4], from.rotation[7]},
                        {from.rotation[2], from.rotation[5], from.rotation[8]}};
  for (int c = 0; c < 3; ++c) {
    const Vec3 r = test::rotate(cols[c], k, angle);
    to.rotation[c] = r.x;
    to.rotation[3 + c] = r.y;
    to.rotation[6 + c] = r.z;
  }
  return {from, to};
}

struct Counts {
  std::size_t queries = 0, hits = 0, independent = 0, startTouches = 0;
};

Counts checkFirstContact(const TriangleMesh& bone, std::size_t n, std::size_t independentEvery, std::uint64_t seed) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  // Parametric reamers (searched through their ideal solid) and a reamer read as a plain solid (no ideal
  // solid: the two trees are paired), so both search paths meet the brute force.
  const ReamerModel reamers[3] = {ReamerModel::fromSpec(test::smallSpec(false)), ReamerModel::fromSpec(test::smallSpec(true)),
                                  ReamerModel::fromSolid(buildCuttingSolid(test::smallSpec(false)))};
  std::mt19937_64 rng(seed);
  Counts c;
  for (std::size_t i = 0; i < n; ++i) {
    const ReamerModel& reamer = reamers[i % 3];
    const auto [from, to] = randomMotion(bone, rng, i);
    const FirstContactResult ref = bruteForceFirstContact(bone, reamer, from, to);
    const FirstContactResult got = queryFirstContact(bvh, reamer, from, to);
    EXPECT_EQ(got.hit, ref.hit) << "query " << i << " t " << got.t << " vs " << ref.t;
    if (got.hit && ref.hit) {
      EXPECT_NEAR(got.t, ref.t, 1e-9) << "query " << i;
    }
    if (got.hit && got.t == 0) {
      ++c.startTouches;
      EXPECT_EQ(got.feature, ContactFeature::Initial) << "query " << i;
      EXPECT_TRUE(surfacesTouch(bone, reamer, from)) << "query " << i;
    }
    if (got.hit) {
      EXPECT_NEAR(norm(got.normal), 1.0, 1e-9);
      EXPECT_GE(got.t, 0.0);
      EXPECT_LE(got.t, 1.0);
      // The contact point lies on the bone triangle reported (the search names triangles by their place in
      // the tree's leaves and must turn that back into the slot).
      EXPECT_LT(got.boneSlot, bone.triangles.size()) << "query " << i;
      if (got.boneSlot >= bone.triangles.size()) return c;
      const Triangle& bt = bone.triangles[got.boneSlot];
      const Vec3 onTriangle = closestPointOnTriangle(got.point, bone.vertices[bt[0]], bone.vertices[bt[1]], bone.vertices[bt[2]]);
      EXPECT_LE(norm(got.point - onTriangle), 1e-7 * (1 + norm(got.point))) << "query " << i << " t " << got.t;
    }
    if (i % independentEvery == 0) {
      // Independent of the event solver: touching at t, and (when t > 0) apart a little earlier; no contact:
      // apart all along the path (sampled).
      if (got.hit) {
        EXPECT_TRUE(surfacesTouch(bone, reamer, interpolateMotion(from, to, got.t))) << "query " << i;
        if (got.t > 1e-6) {
          EXPECT_FALSE(surfacesTouch(bone, reamer, interpolateMotion(from, to, got.t - 1e-6))) << "query " << i;
        }
      } else {
        for (int k = 0; k <= 16; ++k)
          EXPECT_FALSE(surfacesTouch(bone, reamer, interpolateMotion(from, to, k / 16.0))) << "query " << i;
      }
      ++c.independent;
    }
    if (::testing::Test::HasFailure()) return c;
    ++c.queries;
    c.hits += got.hit;
  }
  return c;
}

Counts checkPenetration(const TriangleMesh& bone, bool closed, std::size_t n, std::size_t independentEvery,
                        std::uint64_t seed) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  // The parametric reamers take the face-as-height-field path, the solid read from a mesh the general one.
  const ReamerModel reamers[3] = {ReamerModel::fromSpec(test::smallSpec(false)), ReamerModel::fromSpec(test::smallSpec(true)),
                                  ReamerModel::fromSolid(buildCuttingSolid(test::smallSpec(false)))};
  EXPECT_TRUE(reamers[0].capShadow() && reamers[1].capShadow());
  EXPECT_FALSE(reamers[2].capShadow());
  std::mt19937_64 rng(seed);
  Counts c;
  for (std::size_t i = 0; i < n; ++i) {
    const ReamerModel& reamer = reamers[i % 3];
    const RigidTransform T = toTransform(test::poseNearSurface(bone, rng, -4, 1, 30));
    const PenetrationResult ref = bruteForceAxialPenetration(bone, reamer, T, closed);
    const PenetrationResult got = queryAxialPenetration(bvh, reamer, T, closed);
    const double tol = kChainToleranceRelative * reamer.radius();
    EXPECT_EQ(got.penetrating, ref.penetrating) << "query " << i;
    EXPECT_EQ(got.enclosed, ref.enclosed) << "query " << i;
    EXPECT_NEAR(got.depthMm, ref.depthMm, tol) << "query " << i;
    if (i % independentEvery == 0 && got.penetrating && !got.enclosed) {
      // Backed out by the depth (+ a hair) the surfaces are apart; a hair less they still touch.
      auto backed = [&](double d) {
        RigidTransform b = T;
        b.translation = T.translation + got.backOut * d;
        return b;
      };
      EXPECT_FALSE(surfacesTouch(bone, reamer, backed(got.depthMm + 1e-6))) << "query " << i;
      if (got.depthMm > 1e-6) {
        EXPECT_TRUE(surfacesTouch(bone, reamer, backed(got.depthMm - 1e-6))) << "query " << i;
      }
      ++c.independent;
    }
    if (::testing::Test::HasFailure()) return c;
    ++c.queries;
    c.hits += got.depthMm > 0;
  }
  return c;
}

}  // namespace

TEST(collisionFirstContactProperty, Sphere) {
  const Counts c = checkFirstContact(sphere(), kSphereQueries, 40, 31);
  EXPECT_EQ(c.queries, kSphereQueries);
  EXPECT_GT(c.startTouches, kSphereQueries / 20);
  EXPECT_GT(c.hits, 1000u);
  EXPECT_LT(c.hits, 3300u);
}
TEST(collisionFirstContactProperty, Slab) {
  const Counts c = checkFirstContact(slab(), kSlabQueries, 40, 32);
  EXPECT_EQ(c.queries, kSlabQueries);
  EXPECT_GT(c.startTouches, kSlabQueries / 20);
  EXPECT_GT(c.hits, 1000u);
}
TEST(collisionFirstContactProperty, BundledScapula) {
  const Counts c = checkFirstContact(scapula(), kScapulaQueries, 40, 33);
  EXPECT_EQ(c.queries, kScapulaQueries);
  EXPECT_GT(c.startTouches, kScapulaQueries / 20);
  EXPECT_GT(c.hits, 1000u);
}

TEST(collisionPenetrationProperty, SphereClosed) {
  const Counts c = checkPenetration(sphere(), true, kSphereQueries, 40, 41);
  EXPECT_EQ(c.queries, kSphereQueries);
  EXPECT_GT(c.hits, 1000u);
}
TEST(collisionPenetrationProperty, SlabClosed) {
  const Counts c = checkPenetration(slab(), true, kSlabQueries, 40, 42);
  EXPECT_EQ(c.queries, kSlabQueries);
  EXPECT_GT(c.hits, 1000u);
}
TEST(collisionPenetrationProperty, BundledScapulaOpen) {
  const Counts c = checkPenetration(scapula(), false, kScapulaQueries, 40, 43);
  EXPECT_EQ(c.queries, kScapulaQueries);
  EXPECT_GT(c.hits, 1000u);
}

// Pressed into a bone that runs parallel to it, where every pair of the contact starts near 0 and many
// end near the depth: the cap (sphere radius 16) 0.05-0.5 mm into the wall of a 17 mm spherical cavity
// (triangles turned inwards: the bone is around the hole), the flat reamer into the slab's top within 2
// degrees of parallel. The sweep's node bounds from the two trees' slabs are tested where they prune most.
TEST(collisionPenetrationProperty, PressedIntoAParallelBone) {
  const ParallelBones bones(3);
  const Vec3& o = bones.centre;
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> u(-1, 1);
  auto unit = [&] { return randomUnit(rng); };
  std::size_t deep = 0;
  for (int i = 0; i < 400; ++i) {
    const bool cup = i % 2 == 0, general = i % 4 >= 2;  // each reamer on its face path and on the general one
    const double press = 0.05 + 0.45 * std::abs(u(rng));
    Pose p;
    if (cup) {  // sphere centre = tip - 16 axis, 1 mm + press from the cavity's centre (a hair off the axis)
      p.axis = unit();
      p.tip = o + p.axis * (17 + press) + unit() * (0.3 * std::abs(u(rng)));
    } else {
      p.axis = normalized(Vec3{0, 0, -1} + unit() * std::tan(2 * 3.14159265358979 / 180 * std::abs(u(rng))));
      p.tip = {8 * u(rng), 8 * u(rng), 20 - press};
    }
    p.rollDeg = 180 * u(rng);
    const RigidTransform T = toTransform(p);
    const TriangleMesh& bone = cup ? bones.cavity : slab();
    const ReamerModel& reamer = general ? (cup ? bones.roundSolid : bones.flatSolid) : (cup ? bones.round : bones.flat);
    const PenetrationResult ref = bruteForceAxialPenetration(bone, reamer, T, true);
    const PenetrationResult got = queryAxialPenetration(cup ? bones.cavityBvh : bones.slabBvh, reamer, T, true);
    EXPECT_EQ(got.penetrating, ref.penetrating) << "query " << i;
    EXPECT_NEAR(got.depthMm, ref.depthMm, kChainToleranceRelative * reamer.radius()) << "query " << i;
    if (::testing::Test::HasFailure()) return;
    deep += ref.depthMm > 0.04;
  }
  EXPECT_GT(deep, 330u);  // nearly all pressed in, as set up
}

// The face path where it differs most from the general one: a bone much finer than the reamer's facets (most
// bone triangles within one face triangle's shadow), pressed by a cap of nearly its curvature and tilted,
// so that many triangles end within the facets' sag of the depth; and a coarse one, whose triangles span
// several face triangles. Both paths and the brute force agree; the face path solves fewer triangles.
TEST(collisionPenetrationProperty, FacePathAgreesWithTheGeneralPathOnFineAndCoarseBones) {
  for (int subdivisions : {1, 5}) {
    const ParallelBones bones(subdivisions);
    const Vec3& o = bones.centre;
    std::mt19937_64 rng(45 + subdivisions);
    std::uniform_real_distribution<double> u(-1, 1);
    std::size_t facePairs = 0, generalPairs = 0, deep = 0;
    for (int i = 0; i < 120; ++i) {
      Pose p;
      p.axis = randomUnit(rng);
      p.tip = o + p.axis * (17 + 0.05 + 0.6 * std::abs(u(rng))) + randomUnit(rng) * (0.5 * std::abs(u(rng)));
      p.axis = normalized(p.axis + randomUnit(rng) * std::tan(10 * kPi / 180 * std::abs(u(rng))));
      p.rollDeg = 180 * u(rng);
      const RigidTransform T = toTransform(p);
      const PenetrationResult face = queryAxialPenetration(bones.cavityBvh, bones.round, T, true);
      const PenetrationResult general = queryAxialPenetration(bones.cavityBvh, bones.roundSolid, T, true);
      const double tol = kChainToleranceRelative * bones.round.radius();
      EXPECT_EQ(face.penetrating, general.penetrating) << "subdivisions " << subdivisions << " query " << i;
      EXPECT_EQ(face.enclosed, general.enclosed) << "subdivisions " << subdivisions << " query " << i;
      EXPECT_NEAR(face.depthMm, general.depthMm, tol) << "subdivisions " << subdivisions << " query " << i;
      if (i % 10 == 0) {
        const PenetrationResult ref = bruteForceAxialPenetration(bones.cavity, bones.round, T, true);
        EXPECT_NEAR(face.depthMm, ref.depthMm, tol) << "subdivisions " << subdivisions << " query " << i;
      }
      if (::testing::Test::HasFailure()) return;
      facePairs += face.trianglePairs;
      generalPairs += general.trianglePairs;
      deep += general.depthMm > 0.03;
    }
    EXPECT_GT(deep, 100u) << "subdivisions " << subdivisions;  // nearly all pressed in, as set up
    if (subdivisions == 5) {
      EXPECT_LT(facePairs, generalPairs);
    }
  }
}

// Motions towards a bone that runs parallel to the reamer, where the hull search's node bounds decide the
// most: the cap fed 0-1.5 mm towards the wall of a 17 mm spherical cavity from 0.05-1 mm away, turning by
// up to 2 degrees, and the flat reamer towards the slab's top within 2 degrees of parallel.
TEST(collisionFirstContactProperty, ApproachingAParallelBone) {
  const ParallelBones bones(3);
  const Vec3& o = bones.centre;
  std::mt19937_64 rng(45);
  std::uniform_real_distribution<double> u(-1, 1);
  auto unit = [&] { return randomUnit(rng); };
  std::size_t hits = 0;
  for (int i = 0; i < 400; ++i) {
    const bool cup = i % 2 == 0;
    const double gap = 0.05 + 0.95 * std::abs(u(rng)), feed = 1.5 * std::abs(u(rng));
    Pose p;
    if (cup) {  // the cap's apex `gap` inside the wall (the cavity's radius 17, the cap's 16)
      p.axis = unit();
      p.tip = o + p.axis * (17 - gap) + unit() * (0.3 * std::abs(u(rng)));
    } else {
      p.axis = normalized(Vec3{0, 0, -1} + unit() * std::tan(2 * kPi / 180 * std::abs(u(rng))));
      p.tip = {8 * u(rng), 8 * u(rng), 20 + 0.4 + gap};  // the rim tilts by <= 0.35 mm
    }
    p.rollDeg = 180 * u(rng);
    const RigidTransform from = toTransform(p);
    RigidTransform to = from;
    to.translation = p.tip + p.axis * feed;
    const Vec3 k = unit();
    const double angle = 2 * kPi / 180 * std::abs(u(rng));
    for (int c = 0; c < 3; ++c) {
      const Vec3 r = test::rotate({from.rotation[c], from.rotation[3 + c], from.rotation[6 + c]}, k, angle);
      to.rotation[c] = r.x;
      to.rotation[3 + c] = r.y;
      to.rotation[6 + c] = r.z;
    }
    const TriangleMesh& bone = cup ? bones.cavity : slab();
    const ReamerModel& reamer = cup ? bones.round : bones.flat;
    const FirstContactResult ref = bruteForceFirstContact(bone, reamer, from, to);
    const FirstContactResult got = queryFirstContact(cup ? bones.cavityBvh : bones.slabBvh, reamer, from, to);
    EXPECT_EQ(got.hit, ref.hit) << "query " << i;
    if (got.hit && ref.hit) {
      EXPECT_NEAR(got.t, ref.t, 1e-9) << "query " << i;
    }
    if (::testing::Test::HasFailure()) return;
    hits += got.hit;
  }
  EXPECT_GT(hits, 100u);
  EXPECT_LT(hits, 350u);
}

// A turn of more than 90 degrees is searched in segments (MotionPlan). Here the first segment's sweep stays
// far above a slab and reaches no bone, so the query skips its search, and the contact comes in the second:
// the time must still be the brute force's, past the middle.
TEST(collisionFirstContact, TurnMeetingTheBoneOnlyInItsSecondSegment) {
  for (const bool flat : {false, true}) {
    const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(flat));
    const TriangleMesh slab = test::makeBox({-60, -60, -20}, {60, 60, -0.05});
    RigidTransform from;
    from.translation = {0, 0, 200};
    RigidTransform to;  // at the origin, turned by 170 degrees about x
    const double angle = 170 * kPi / 180;
    for (int c = 0; c < 3; ++c) {
      const Vec3 r = test::rotate({from.rotation[c], from.rotation[3 + c], from.rotation[6 + c]}, {1, 0, 0}, angle);
      to.rotation[c] = r.x;
      to.rotation[3 + c] = r.y;
      to.rotation[6 + c] = r.z;
    }
    const FirstContactResult ref = bruteForceFirstContact(slab, reamer, from, to);
    ASSERT_TRUE(ref.hit) << "flat " << flat;
    ASSERT_GT(ref.t, 0.5) << "flat " << flat;
    const TriangleBvh bvh = TriangleBvh::fromMesh(slab);
    const FirstContactResult got = queryFirstContact(bvh, reamer, from, to);
    EXPECT_TRUE(got.hit) << "flat " << flat;
    EXPECT_NEAR(got.t, ref.t, 1e-9) << "flat " << flat;
    // Stopped halfway, the same motion meets nothing.
    const RigidTransform half = interpolateMotion(from, to, 0.5);
    EXPECT_FALSE(queryFirstContact(bvh, reamer, from, half).hit) << "flat " << flat;
  }
}

// The reamer's body (not its cutting face) already in the bone: a box through the cylinder wall, below the
// cap. A parametric reamer tests the body and back at the start only when its sweep meets bone its ideal
// solid reaches there (FirstContact.cpp), so this is the case where that test has to fire: time 0, whatever
// the motion, as the brute force says.
TEST(collisionFirstContact, BodyTouchingAtTheStartIsTimeZero) {
  for (const bool flat : {false, true}) {
    const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(flat));
    const ReamerModel::IdealSolid& id = reamer.idealSolid();
    ASSERT_TRUE(id.valid);
    const double capBase = flat ? 0.0 : id.capBaseZ;
    ASSERT_LT(id.zBack + 2, capBase - 1);
    const TriangleMesh box = test::makeBox({id.radius - 0.5, -1, id.zBack + 1}, {id.radius + 4, 1, capBase - 1});
    const TriangleBvh bvh = TriangleBvh::fromMesh(box);
    const RigidTransform from;  // the reamer's own frame
    for (const Vec3& move : {Vec3{-5, 0, 0}, Vec3{5, 0, 0}, Vec3{0, 0, 3}, Vec3{0, 0, 0}}) {
      RigidTransform to = from;
      to.translation = move;
      const FirstContactResult got = queryFirstContact(bvh, reamer, from, to);
      const FirstContactResult ref = bruteForceFirstContact(box, reamer, from, to);
      ASSERT_TRUE(ref.hit);
      EXPECT_EQ(ref.t, 0.0);
      EXPECT_TRUE(got.hit) << "flat " << flat;
      EXPECT_EQ(got.t, 0.0) << "flat " << flat;
      EXPECT_EQ(got.feature, ContactFeature::Initial) << "flat " << flat;
      EXPECT_TRUE(surfacesTouch(box, reamer, from));
    }
    // Moved 0.3 mm clear of the wall, the start is apart and the contact comes later.
    const TriangleMesh clear = test::makeBox({id.radius + 0.3, -1, id.zBack + 1}, {id.radius + 4, 1, capBase - 1});
    RigidTransform to = from;
    to.translation = {1, 0, 0};
    const FirstContactResult got = queryFirstContact(TriangleBvh::fromMesh(clear), reamer, from, to);
    const FirstContactResult ref = bruteForceFirstContact(clear, reamer, from, to);
    ASSERT_TRUE(ref.hit && got.hit);
    EXPECT_GT(got.t, 0.2);
    EXPECT_NEAR(got.t, ref.t, 1e-9);
  }
}

// FirstContactResult::work counts what the query did (the bench reports them per kind of motion): a motion that
// starts touching stops at the face's start test; one that meets nothing is settled by the sweep pass, one node
// per segment when even the root is out of reach (the counts of a segment skipped without its search are kept);
// one that meets the bone on the way is searched, and every exact pair passed the pair bounds first.
TEST(collisionFirstContact, WorkCountsSayWhatTheQueryDid) {
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(false));
  const TriangleMesh slab = test::makeBox({-60, -60, -20}, {60, 60, -0.05});
  const TriangleBvh bvh = TriangleBvh::fromMesh(slab);
  auto turnedAboutX = [](const RigidTransform& from, double degrees) {
    RigidTransform to = from;
    for (int c = 0; c < 3; ++c) {
      const Vec3 r = test::rotate({from.rotation[c], from.rotation[3 + c], from.rotation[6 + c]}, {1, 0, 0},
                                  degrees * kPi / 180);
      to.rotation[c] = r.x;
      to.rotation[3 + c] = r.y;
      to.rotation[6 + c] = r.z;
    }
    return to;
  };
  // The reamer's own frame points its feed along +z; turned by 180 degrees about x it faces the slab (-z).
  // A feed straight down from the tip at height z0 to z1:
  const RigidTransform down = turnedAboutX(RigidTransform{}, 180);
  auto feedDown = [&](double z0, double z1) {
    RigidTransform from = down, to = down;
    from.translation = {0, 0, z0};
    to.translation = {0, 0, z1};
    return queryFirstContact(bvh, reamer, from, to);
  };

  // Touching at the start: the tip 1 mm into the slab.
  const FirstContactResult touching = feedDown(-1, -2);
  ASSERT_TRUE(touching.hit);
  EXPECT_EQ(touching.t, 0.0);
  EXPECT_GE(touching.work.startTestNodes, 1u);
  EXPECT_EQ(touching.work.sweepPassNodes, 0u);
  EXPECT_EQ(touching.work.hullBounds, 0u);
  EXPECT_EQ(touching.work.pairBounds, 0u);
  EXPECT_EQ(touching.trianglePairs, 0u);

  // Meeting nothing: a 170-degree turn about the tip 200 mm above the slab, two segments, neither in reach.
  RigidTransform high;
  high.translation = {0, 0, 200};
  const FirstContactResult none = queryFirstContact(bvh, reamer, high, turnedAboutX(high, 170));
  ASSERT_FALSE(none.hit);
  EXPECT_EQ(none.work.startTestNodes, 0u);
  EXPECT_EQ(none.work.sweepPassNodes, 2u);
  EXPECT_EQ(none.work.hullBounds, 0u);
  EXPECT_EQ(none.work.pairBounds, 0u);
  EXPECT_EQ(none.trianglePairs, 0u);

  // Meeting the slab on the way: fed 3 mm down from 1 mm above it.
  const FirstContactResult during = feedDown(1, -2);
  ASSERT_TRUE(during.hit);
  EXPECT_GT(during.t, 0.0);
  EXPECT_GE(during.work.sweepPassNodes, 1u);
  EXPECT_GE(during.work.hullBounds, 1u);
  EXPECT_GE(during.trianglePairs, 1u);
  EXPECT_GE(during.work.pairBounds, during.trianglePairs);
}

// A knife edge under the cap: the bone's two long faces run within 0.3 degrees of the axis, so their shadows
// are too thin for the face path's height field and they are paired with the face triangles over them; the
// depth is decided on the edge they share.
TEST(collisionPenetrationProperty, KnifeEdgeAlongTheAxis) {
  TriangleMesh wedge;
  wedge.vertices = {{-5, 0, 0}, {5, 0, 0}, {-5, -0.1, -20}, {5, -0.1, -20}, {-5, 0.1, -20}, {5, 0.1, -20}};
  wedge.triangles = {{0, 1, 3}, {0, 3, 2}, {0, 4, 5}, {0, 5, 1}, {2, 3, 5}, {2, 5, 4}, {0, 2, 4}, {1, 5, 3}};
  const TriangleBvh bvh = TriangleBvh::fromMesh(wedge);
  const ParallelBones bones(1);
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t deep = 0;
  for (int i = 0; i < 200; ++i) {
    const bool cup = i % 2 == 0;
    const ReamerModel& reamer = cup ? bones.round : bones.flat;
    const double press = 0.05 + 0.5 * std::abs(u(rng));
    Pose p;
    p.axis = normalized(Vec3{0, 0, -1} + randomUnit(rng) * std::tan(0.2 * kPi / 180 * std::abs(u(rng))));
    p.tip = Vec3{3 * u(rng), 2 * u(rng), -press};
    p.rollDeg = 180 * u(rng);
    const RigidTransform T = toTransform(p);
    const PenetrationResult ref = bruteForceAxialPenetration(wedge, reamer, T, true);
    const PenetrationResult got = queryAxialPenetration(bvh, reamer, T, true);
    EXPECT_EQ(got.penetrating, ref.penetrating) << "query " << i;
    EXPECT_NEAR(got.depthMm, ref.depthMm, kChainToleranceRelative * reamer.radius()) << "query " << i;
    if (::testing::Test::HasFailure()) return;
    deep += ref.depthMm > 0.04;
  }
  EXPECT_GT(deep, 100u);
}
