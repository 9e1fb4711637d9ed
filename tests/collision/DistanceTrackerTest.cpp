// FaceDistanceTracker (query 2 along a sequence of poses) against the one-pose query and the brute force:
// hand-held walks that hover, press into the bone and jump; a bone edited between two queries; two reamers
// in turn. The tracker answers from the triangles its last search collected only while a motion bound
// proves no other triangle nearer, so every answer must equal the full query's.
#include <gtest/gtest.h>

#include <random>

#include "CollisionFixtures.h"
#include "PropertyBones.h"
#include "reamsim/collision/BruteForce.h"
#include "reamsim/collision/DistanceQuery.h"

using namespace reamsim;
using namespace reamsim::test;

namespace {

struct WalkCounts {
  std::size_t queries = 0, searches = 0, touching = 0, apart = 0;
};

// Walks of `steps` ticks from poses near the surface: a slow drift along the feed (into the bone and back),
// tremor of up to 0.03 mm and 0.1 degree a tick, and every 60 ticks a jump of up to 3 mm.
WalkCounts walk(const TriangleMesh& bone, int walks, int steps, std::uint64_t seed,
               double marginMm = FaceDistanceTracker::kDefaultMarginMm) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  const ReamerModel reamers[2] = {ReamerModel::fromSpec(smallSpec(false)), ReamerModel::fromSpec(smallSpec(true))};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  WalkCounts c;
  for (int w = 0; w < walks; ++w) {
    const ReamerModel& reamer = reamers[w % 2];
    FaceDistanceTracker tracker(marginMm);
    Pose p = poseNearSurface(bone, rng, -0.5, 2.5, 20);
    const double feed = 0.02 * u(rng);
    for (int i = 0; i < steps; ++i) {
      if (i % 60 == 59) {
        p.tip += randomUnit(rng) * (3 * std::abs(u(rng)));
      } else {
        p.tip += p.axis * feed + randomUnit(rng) * (0.03 * std::abs(u(rng)));
        p.axis = normalized(p.axis + randomUnit(rng) * (0.1 * 3.14159265358979 / 180 * std::abs(u(rng))));
      }
      const RigidTransform T = toTransform(p);
      const DistanceResult ref = queryFaceDistance(bvh, reamer, T);
      const DistanceResult got = tracker.query(bvh, reamer, T);
      EXPECT_EQ(got.found, ref.found) << "walk " << w << " tick " << i;
      EXPECT_NEAR(got.distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << "walk " << w << " tick " << i;
      // The pair is a real pair at that distance.
      EXPECT_NEAR(norm(got.onReamer - got.onBone), got.distanceMm, 1e-9 * (1 + got.distanceMm));
      if (i % 25 == 0) {  // and the one-pose query is itself right (the property tests check it at length)
        const DistanceResult brute = bruteForceFaceDistance(bone, reamer, T);
        EXPECT_NEAR(got.distanceMm, brute.distanceMm, 1e-9 * (1 + brute.distanceMm)) << "walk " << w << " tick " << i;
      }
      if (::testing::Test::HasFailure()) return c;
      ++c.queries;
      ++(ref.distanceMm == 0 ? c.touching : c.apart);
    }
    c.searches += tracker.stats().searches;
  }
  return c;
}

void expectWalksExact(const TriangleMesh& bone, std::uint64_t seed) {
  const WalkCounts c = walk(bone, 12, 300, seed);
  EXPECT_EQ(c.queries, 12u * 300u);
  // Both outcomes were met, and most ticks were answered without a search (else the shortcut went untested).
  EXPECT_GT(c.touching, 200u);
  EXPECT_GT(c.apart, 1000u);
  EXPECT_LT(c.searches, c.queries / 2);
}

}  // namespace

TEST(collisionDistanceTracker, WalksOverTheSphere) { expectWalksExact(sphere(), 31); }
TEST(collisionDistanceTracker, WalksOverTheSlab) { expectWalksExact(slab(), 32); }
TEST(collisionDistanceTracker, WalksOverTheBundledScapula) { expectWalksExact(scapula(), 33); }

// The collected set's bookkeeping with margins far from the default (a set of one or two triangles, and one
// of hundreds), and a bone ~5 m from the origin, where the motion bound's rounding pad matters.
TEST(collisionDistanceTracker, OtherMarginsAndFarFromTheOrigin) {
  for (double margin : {1e-6, 0.02, 2.0}) {
    const WalkCounts c = walk(scapula(), 4, 200, 36, margin);
    EXPECT_EQ(c.queries, 800u) << "margin " << margin;
  }
  TriangleMesh far = sphere();
  for (Vec3& v : far.vertices) v += Vec3{4000, -2500, 1500};
  const WalkCounts c = walk(far, 6, 300, 37);
  EXPECT_EQ(c.queries, 1800u);
  EXPECT_LT(c.searches, c.queries / 2);
}

// The reamer seated in the concave cavity, turning about its centre: every bone face is nearly as far from
// the cap as the nearest, so the collected set is large and the proof is tight.
TEST(collisionDistanceTracker, SeatedInAConcaveBone) {
  const ParallelBones bones(4);
  std::mt19937_64 rng(34);
  std::uniform_real_distribution<double> u(-1, 1);
  FaceDistanceTracker tracker;
  Pose p;
  p.axis = randomUnit(rng);
  Vec3 offset{0.3, 0, 0};
  for (int i = 0; i < 1500; ++i) {
    p.axis = normalized(p.axis + randomUnit(rng) * 0.002);
    offset += randomUnit(rng) * 0.01;
    if (norm(offset) > 0.9) offset = offset * (0.9 / norm(offset));
    p.tip = bones.centre + offset + p.axis * 16;  // sphere centre = tip - 16 axis
    const RigidTransform T = toTransform(p);
    const DistanceResult ref = queryFaceDistance(bones.cavityBvh, bones.round, T);
    const DistanceResult got = tracker.query(bones.cavityBvh, bones.round, T);
    ASSERT_GT(ref.distanceMm, 0) << "tick " << i;
    ASSERT_NEAR(got.distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << "tick " << i;
  }
  EXPECT_LT(tracker.stats().searches, 1500u / 2);
}

// At a constant gap the distance does not change while the nearest bone triangle does: the tilted flat
// face precessing about its tip (turning only: its lowest rim point circles over the slab), then sliding
// sideways (moving only). Answered from a stale set, the distance would grow; the motion bound (both its
// terms) must send the tracker back to the tree in time.
TEST(collisionDistanceTracker, TurningAndSlidingAtAConstantGap) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(block({-30, -30, 0}, {30, 30, 20}, 60));  // 1 mm triangles
  const ReamerModel reamer = ReamerModel::fromSpec(smallSpec(true, 24, 4));
  FaceDistanceTracker tracker;
  const double pi = 3.14159265358979323846, tilt = 10 * pi / 180;
  Pose p;
  p.tip = {0, 0, 23};
  std::size_t ticks = 0;
  auto check = [&](const char* phase, int i) {
    const RigidTransform T = toTransform(p);
    const DistanceResult ref = queryFaceDistance(bvh, reamer, T);
    ASSERT_GT(ref.distanceMm, 0.5);
    ASSERT_NEAR(tracker.query(bvh, reamer, T).distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << phase << " tick " << i;
    ++ticks;
  };
  for (int i = 0; i < 720; ++i) {  // the rim's lowest point moves ~0.05 mm a tick
    const double phi = i * pi / 720;
    p.axis = {std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), -std::cos(tilt)};
    check("turning", i);
  }
  for (int i = 0; i < 400; ++i) {
    p.tip += Vec3{0.02, 0.01, 0};
    check("sliding", i);
  }
  EXPECT_EQ(ticks, 1120u);
  EXPECT_GT(tracker.stats().searches, 20u);       // the nearest triangle changed, and the tracker saw it
  EXPECT_LT(tracker.stats().searches, ticks / 2);  // yet most ticks were answered from the set
}

// An edit of the bone between two queries at the same pose: a triangle put in front of the face, then taken
// away with the nearest ones under it. The tracker must see each (TriangleBvh::revision), not answer from
// the triangles it collected before.
TEST(collisionDistanceTracker, FollowsTheBoneThroughEdits) {
  TriangleBvh bvh = TriangleBvh::fromMesh(slab());
  const ReamerModel reamer = ReamerModel::fromSpec(smallSpec(true));
  Pose p;
  p.axis = {0, 0, -1};
  p.tip = {1, 2, 20 + 1.5};  // the flat face 1.5 mm over the slab's top (z = 20)
  const RigidTransform T = toTransform(p);
  FaceDistanceTracker tracker;
  const double before = tracker.query(bvh, reamer, T).distanceMm;
  ASSERT_NEAR(before, queryFaceDistance(bvh, reamer, T).distanceMm, 1e-12);
  EXPECT_NEAR(tracker.query(bvh, reamer, T).distanceMm, before, 1e-12);  // answered from the collected set

  // A small triangle 0.5 mm under the face.
  const std::uint32_t added = static_cast<std::uint32_t>(bvh.slotCapacity());
  bvh.update({}, {added}, {BvhTriangle{{1, 2, 21}, {1.5, 2, 21}, {1, 2.5, 21}}});
  const double nearer = tracker.query(bvh, reamer, T).distanceMm;
  EXPECT_NEAR(nearer, queryFaceDistance(bvh, reamer, T).distanceMm, 1e-12);
  EXPECT_NEAR(nearer, 0.5, 1e-6);
  EXPECT_NEAR(tracker.query(bvh, reamer, T).distanceMm, nearer, 1e-12);

  // It goes again, and with it the slab's top triangles nearest the face: the distance grows.
  const DistanceResult top = queryFaceDistance(bvh, reamer, T);
  std::vector<std::uint32_t> removed{added};
  for (std::uint32_t s = 0; s < slab().triangles.size(); ++s) {
    const BvhTriangle& t = bvh.triangle(s);
    if (t.a.z == 20 && t.b.z == 20 && t.c.z == 20) removed.push_back(s);
  }
  ASSERT_GT(removed.size(), 1u);
  (void)top;
  bvh.update(removed, {}, {});
  const DistanceResult after = tracker.query(bvh, reamer, T);
  const DistanceResult ref = queryFaceDistance(bvh, reamer, T);
  EXPECT_NEAR(after.distanceMm, ref.distanceMm, 1e-12);
  EXPECT_GT(after.distanceMm, 1.5 + 1e-3);
  EXPECT_EQ(tracker.stats().searches, 3u);  // one per revision of the tree

  // A slot removed and added again in one update, now right under the face: same slot, other geometry.
  const std::uint32_t reused = removed[1];
  bvh.update({}, {reused}, {BvhTriangle{{1, 2, 20.8}, {1.6, 2, 20.8}, {1, 2.6, 20.8}}});
  (void)tracker.query(bvh, reamer, T);
  bvh.update({reused}, {reused}, {BvhTriangle{{1, 2, 21.2}, {1.6, 2, 21.2}, {1, 2.6, 21.2}}});
  const double reusedDistance = tracker.query(bvh, reamer, T).distanceMm;
  EXPECT_NEAR(reusedDistance, queryFaceDistance(bvh, reamer, T).distanceMm, 1e-12);
  EXPECT_NEAR(reusedDistance, 0.3, 1e-6);
}

// Two reamers in turn at the same poses (a tool change): each answer is that reamer's.
TEST(collisionDistanceTracker, AnotherReamerIsNotAnsweredFromTheFirstOnesSet) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(sphere());
  const ReamerModel round = ReamerModel::fromSpec(smallSpec(false)), flat = ReamerModel::fromSpec(smallSpec(true));
  std::mt19937_64 rng(35);
  FaceDistanceTracker tracker;
  for (int i = 0; i < 200; ++i) {
    const RigidTransform T = toTransform(poseNearSurface(sphere(), rng, 0.2, 2, 10));
    for (const ReamerModel* r : {&round, &flat, &round}) {
      const DistanceResult ref = queryFaceDistance(bvh, *r, T);
      ASSERT_NEAR(tracker.query(bvh, *r, T).distanceMm, ref.distanceMm, 1e-9 * (1 + ref.distanceMm)) << "pose " << i;
    }
  }
}

TEST(collisionDistanceTracker, EmptyBoneFindsNothing) {
  const TriangleBvh empty;
  const ReamerModel reamer = ReamerModel::fromSpec(smallSpec(false));
  FaceDistanceTracker tracker;
  EXPECT_FALSE(tracker.query(empty, reamer, RigidTransform{}).found);
}
