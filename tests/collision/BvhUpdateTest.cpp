// The BVH following a bone being cut: local updates from MeshDelta / slot changes / commitByDiff, checked
// against a brute-force view of the same BoneState after every cut, and its quality over thousands of cuts.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "../core/MovedCornerEdit.h"
#include "CollisionFixtures.h"
#include "reamsim/collision/BoneCollider.h"
#include "reamsim/collision/BruteForce.h"
#include "reamsim/collision/BvhRayCast.h"
#include "reamsim/collision/SyntheticCut.h"
#include "reamsim/csg/ReferenceSubtractor.h"

using namespace reamsim;

namespace {

// The state as a plain mesh plus the slot of each mesh triangle (toMesh keeps slot order).
struct Snapshot {
  TriangleMesh mesh;
  std::vector<std::uint32_t> slotOf;
};
Snapshot snapshot(const BoneState& s) {
  Snapshot out{s.toMesh(), {}};
  s.forEachLiveTriangle([&](std::uint32_t slot, const Triangle&) { out.slotOf.push_back(slot); });
  return out;
}

// Queries of every type on the collider agree with the brute force on the state's mesh.
void expectAgreesWithBruteForce(const BoneCollider& collider, const BoneState& state, const ReamerModel& reamer,
                                std::mt19937_64& rng, int queries) {
  const Snapshot snap = snapshot(state);
  ASSERT_EQ(snap.slotOf.size(), collider.bvh().triangleCount());
  for (int i = 0; i < queries; ++i) {
    const RigidTransform T = toTransform(test::poseNearSurface(snap.mesh, rng, -2, 3, 25));
    const OverlapResult ref = bruteForceOverlap(snap.mesh, reamer, T, collider.closed());
    const OverlapResult got = collider.overlap(reamer, T);
    std::vector<std::uint32_t> mapped;
    for (std::uint32_t idx : ref.touchedSlots) mapped.push_back(snap.slotOf[idx]);
    std::sort(mapped.begin(), mapped.end());
    EXPECT_EQ(got.touchedSlots, mapped);
    EXPECT_NEAR(collider.faceDistance(reamer, T).distanceMm, bruteForceFaceDistance(snap.mesh, reamer, T).distanceMm,
                1e-9);
    const Vec3 o = T.translation - T.applyToDirection({0, 0, 1}) * 5.0, dir = T.applyToDirection({0, 0, 1});
    const auto bf = firstHit(snap.mesh, o, dir);
    const auto bv = collider.firstHit(o, dir);
    ASSERT_EQ(bf.has_value(), bv.has_value());
    if (bf) {
      EXPECT_EQ(bf->t, bv->t);
      EXPECT_EQ(snap.slotOf[bf->triangle], bv->triangle);
    }
    EXPECT_EQ(allHits(snap.mesh, o, dir).size(), collider.allHits(o, dir).size());
    if (::testing::Test::HasFailure()) return;
  }
}

double freshSah(const BoneState& s) { return BoneCollider(s).bvh().quality().sahCost; }

}  // namespace

TEST(collisionBvhUpdate, DentCutsKeepTheTreeValidAndTheQueriesExact) {
  BoneState state = BoneState::fromMesh(test::defaultScapula());
  BoneCollider collider(state);
  ASSERT_TRUE(collider.closed());
  ASSERT_EQ(collider.bvh().validate(), "");
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(false, 24, 6));
  std::mt19937_64 rng(5);
  std::size_t changed = 0;
  for (int cut = 0; cut < 40; ++cut) {
    const Snapshot snap = snapshot(state);
    const RigidTransform T = toTransform(test::poseNearSurface(snap.mesh, rng, -1.0, -0.2, 20));
    const OverlapResult touched = collider.overlap(reamer, T);
    if (touched.touchedSlots.empty()) continue;
    const MeshDelta delta = dentDelta(state, touched.touchedSlots, reamer, T);
    DeltaPlacement placement;
    state = state.applyDelta(delta, &placement);
    const BvhUpdateStats stats = collider.applyDelta(state, delta, placement);
    EXPECT_EQ(stats.removed, delta.removedTriangles.size());
    EXPECT_EQ(stats.added, delta.addedTriangles.size());
    ASSERT_EQ(collider.bvh().validate(), "") << "after cut " << cut;
    changed += stats.removed;
    if (cut % 10 == 9) expectAgreesWithBruteForce(collider, state, reamer, rng, 20);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(changed, 1500u);
}

// Thousands of cuts: the tree stays valid, its SAH cost stays close to a fresh build's, and the rebuild work
// stays proportional to the edits.
TEST(collisionBvhUpdate, QualityHoldsOverThousandsOfCuts) {
  BoneState state = BoneState::fromMesh(test::defaultScapula());
  BoneCollider collider(state);
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(false, 16, 4));
  std::mt19937_64 rng(6);
  std::size_t edits = 0, rebuilt = 0, cuts = 0;
  const TriangleMesh original = state.toMesh();
  for (int cut = 0; cut < 2000; ++cut) {
    // Cut where the current surface is: sample the original mesh, then place against the current tree.
    const RigidTransform T = toTransform(test::poseNearSurface(original, rng, -1.5, 0.5, 20));
    const OverlapResult touched = collider.overlap(reamer, T);
    if (touched.touchedSlots.empty()) continue;
    const MeshDelta delta = dentDelta(state, touched.touchedSlots, reamer, T);
    DeltaPlacement placement;
    state = state.applyDelta(delta, &placement);
    const BvhUpdateStats s = collider.applyDelta(state, delta, placement);
    edits += s.removed + s.added;
    rebuilt += s.rebuiltTriangles;
    ++cuts;
    if (cut % 250 == 0) {
      ASSERT_EQ(collider.bvh().validate(), "") << "after cut " << cut;
    }
  }
  ASSERT_EQ(collider.bvh().validate(), "");
  EXPECT_GT(cuts, 1000u);
  const double ratio = collider.bvh().quality().sahCost / freshSah(state);
  std::printf("after %zu cuts (%zu edits, %zu triangles re-sorted): SAH cost %.4f x a fresh build, depth %zu\n", cuts,
              edits, rebuilt, ratio, collider.bvh().quality().maxDepth);
  EXPECT_LT(ratio, 1.3) << "SAH cost relative to a fresh build after " << cuts << " cuts";
  EXPECT_LE(rebuilt, 4 * edits + 2 * state.liveTriangleCount());
  std::mt19937_64 qrng(7);
  expectAgreesWithBruteForce(collider, state, reamer, qrng, 30);
}

// An engine that only returns a whole new mesh (the CGAL reference) goes through commitByDiff and syncTo.
TEST(collisionBvhUpdate, ExactCgalCutsFollowedBySyncTo) {
  const TriangleMesh bone = test::defaultScapula();
  BoneState state = BoneState::fromMesh(bone);
  BoneCollider collider(state);
  std::ifstream in(std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_glenoid.json");
  const nlohmann::json g = nlohmann::json::parse(in);
  const Vec3 centre{g["centre_mm"][0], g["centre_mm"][1], g["centre_mm"][2]};
  const Vec3 outward{g["outward_axis"][0], g["outward_axis"][1], g["outward_axis"][2]};
  ReamerSpec spec = test::smallSpec(false, 32, 6);
  spec.diameterMm = 30;
  spec.sphereRadiusMm = 30;
  const ReamerModel reamer = ReamerModel::fromSpec(spec);
  ReferenceSubtractor engine(bone);
  std::mt19937_64 rng(8);
  for (int step = 1; step <= 3; ++step) {
    Pose p;
    p.axis = -outward;
    p.tip = centre + outward * 1.0 + p.axis * (0.6 * step);
    const RigidTransform T = toTransform(p);
    TriangleMesh tool = reamer.solid();
    for (Vec3& v : tool.vertices) v = T.apply(v);
    const ReferenceCut cut = engine.subtract(tool);
    ASSERT_TRUE(cut.changed) << "step " << step;
    const BoneState next = BoneState::commitByDiff(state, engine.mesh());
    const SlotChanges changes = diffSlots(collider.bvh(), next);
    EXPECT_FALSE(changes.removed.empty());
    EXPECT_FALSE(changes.added.empty());
    // What syncTo follows: the slots that differ from the state the tree holds, found by chunk identity.
    const SlotChanges followed = collider.changesTo(next);
    EXPECT_EQ(followed.removed, changes.removed);
    EXPECT_EQ(followed.added, changes.added);
    const BvhUpdateStats s = collider.syncTo(next);
    EXPECT_EQ(s.removed, changes.removed.size());
    EXPECT_EQ(s.added, changes.added.size());
    state = next;
    ASSERT_EQ(collider.bvh().validate(), "");
    EXPECT_TRUE(diffSlots(collider.bvh(), state).removed.empty());
    // The cut region is where the reamer is: it now touches the new faces, and nothing is left to cut deeper
    // than the cut itself.
    EXPECT_TRUE(collider.overlap(reamer, T, OverlapMode::AnyContact).overlap);
    expectAgreesWithBruteForce(collider, state, reamer, rng, 15);
  }
}

// The graft build sorts added triangles along a Morton curve: coincident centroids (equal codes) and a few
// triangles far from the rest (lopsided splits) must still give a valid tree that finds every triangle.
TEST(collisionBvhUpdate, GraftsOfCoincidentAndScatteredTrianglesStayValid) {
  const TriangleMesh m = test::icosphere(2, 10, {0, 0, 0});
  TriangleBvh bvh = TriangleBvh::fromMesh(m);
  std::vector<std::uint32_t> slots;
  std::vector<BvhTriangle> tris;
  for (std::uint32_t i = 0; i < 64; ++i) {  // 64 copies of one triangle above the sphere
    slots.push_back(1000 + i);
    tris.push_back({{0, 0, 20}, {1, 0, 20}, {0, 1, 20}});
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::uint32_t i = 0; i < 200; ++i) {  // small triangles: most near one point, a few 1000 mm away
    const double spread = i % 50 == 0 ? 1000 : 3;
    const Vec3 c{40 + spread * u(rng), spread * u(rng), spread * u(rng)};
    slots.push_back(2000 + i);
    tris.push_back({c, c + Vec3{0.1, 0, 0}, c + Vec3{0, 0.1, 0}});
  }
  bvh.update({}, slots, tris);
  ASSERT_EQ(bvh.validate(), "");
  EXPECT_EQ(bvh.triangleCount(), m.triangles.size() + slots.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const BvhTriangle& t = tris[i];
    const Vec3 centroid = (t.a + t.b + t.c) * (1.0 / 3);
    const std::vector<MeshHit> hits = allHits(bvh, centroid + Vec3{0, 0, 5}, {0, 0, -1});
    const bool found = std::any_of(hits.begin(), hits.end(), [&](const MeshHit& h) {
      return std::abs(h.point.z - centroid.z) < 1e-9;
    });
    EXPECT_TRUE(found) << "added triangle " << i;
  }
}

TEST(collisionBvhUpdate, InvalidUpdatesAreRejectedAndLeaveTheTreeUnchanged) {
  const TriangleMesh m = test::icosphere(2, 10, {0, 0, 0});
  TriangleBvh bvh = TriangleBvh::fromMesh(m);
  const BvhTriangle t{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(bvh.update({9999}, {}, {}), std::invalid_argument);         // not in the tree
  EXPECT_THROW(bvh.update({3, 3}, {}, {}), std::invalid_argument);         // removed twice
  EXPECT_THROW(bvh.update({}, {5}, {t}), std::invalid_argument);           // already present
  EXPECT_THROW(bvh.update({}, {400, 400}, {t, t}), std::invalid_argument);  // added twice
  EXPECT_THROW(bvh.update({}, {400}, {}), std::invalid_argument);          // sizes differ
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(bvh.update({}, {400}, {{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}}}), std::invalid_argument);
  EXPECT_EQ(bvh.triangleCount(), m.triangles.size());
  EXPECT_EQ(bvh.validate(), "");
  // Removing and re-adding the same slot in one update is allowed.
  bvh.update({5}, {5}, {t});
  EXPECT_EQ(bvh.validate(), "");
  EXPECT_EQ(bvh.triangle(5).b, t.b);
}

TEST(collisionBvhUpdate, EmptyingAndRefillingTheTree) {
  const TriangleMesh m = test::icosphere(1, 10, {0, 0, 0});
  TriangleBvh bvh = TriangleBvh::fromMesh(m);
  std::vector<std::uint32_t> all(m.triangles.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  bvh.update(all, {}, {});
  EXPECT_TRUE(bvh.empty());
  EXPECT_EQ(bvh.validate(), "");
  std::vector<BvhTriangle> tris;
  for (const Triangle& t : m.triangles) tris.push_back({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
  const BvhUpdateStats s = bvh.update({}, all, tris);
  EXPECT_TRUE(s.fullRebuild);
  EXPECT_EQ(bvh.triangleCount(), m.triangles.size());
  EXPECT_EQ(bvh.validate(), "");
  EXPECT_TRUE(insideClosedSurface(bvh, {0, 0, 0}));
}

namespace {
// A fresh build's node order (TriangleBvh::layOutInPairBlocks): the root first, every node's children side by
// side, and below the root and every second level the children's children right after them. Queries rely
// on none of it for their results, only for where their cache misses fall; the tree stays valid and a local
// update works on it as on any other.
TEST(collisionBvhBuild, NodesAreLaidOutInPairBlocks) {
  const TriangleMesh bone = test::defaultScapula();
  TriangleBvh bvh = TriangleBvh::fromMesh(bone);
  ASSERT_EQ(bvh.validate(), "");
  ASSERT_EQ(bvh.root(), 0);
  const auto& nodes = bvh.nodes();
  std::size_t owners = 0, blocks = 0;
  // Walk the owners (the root, then every node two levels below an owner) and check each block.
  std::vector<std::int32_t> stack{bvh.root()};
  while (!stack.empty()) {
    const BvhNode& P = nodes[std::size_t(stack.back())];
    stack.pop_back();
    if (P.isLeaf()) continue;
    ++owners;
    ASSERT_EQ(P.right, P.left + 1);
    std::int32_t next = P.left + 2;
    for (std::int32_t c : {P.left, P.right}) {
      const BvhNode& C = nodes[std::size_t(c)];
      if (C.isLeaf()) continue;
      ASSERT_EQ(C.left, next) << "the children of node " << c << " do not follow its block";
      ASSERT_EQ(C.right, next + 1);
      next += 2;
      stack.push_back(C.left);
      stack.push_back(C.right);
    }
    ++blocks;
  }
  EXPECT_GT(owners, bone.triangles.size() / 16);
  EXPECT_EQ(owners, blocks);
  // A local update on the laid-out tree keeps it valid (grafted nodes go where there is room).
  std::vector<std::uint32_t> removed;
  for (std::uint32_t s = 0; s < 200; ++s) removed.push_back(s * 7);
  bvh.update(removed, {}, {});
  EXPECT_EQ(bvh.validate(), "");
}

// One edit can free a vertex slot, give it to a new vertex and put a triangle with the same corner slots back in
// the slot it left (the default plan's cuts do, three times in 18). Followed by syncTo, the tree must take the
// moved corner: until session 53 changedTriangleSlots saw the same slots as the same triangle, and the tree kept
// the old corners.
TEST(collisionBvhUpdate, SyncToFollowsATriangleBackInItsSlotWithAMovedCorner) {
  const test::MovedCornerEdit e = test::movedCornerEdit();
  BoneCollider collider(e.before);
  collider.syncTo(e.after);
  // A ray up through (0.25, 0.25): with its corner at (0, 0, 1) the triangle lies in x + y + z = 1, z = 0.5 there
  // (the old one: z = 0).
  const std::optional<MeshHit> hit = collider.firstHit({0.25, 0.25, -1}, {0, 0, 1});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->point.z, 0.5, 1e-12);
}
}  // namespace
