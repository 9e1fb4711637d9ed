#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "TestMeshes.h"
#include "reamsim/collision/MeshRayCast.h"

using namespace reamsim;

namespace {
const TriangleMesh kCube = test::makeBox({0, 0, 0}, {1, 1, 1});
}

TEST(collisionMeshRayCast, FirstHitIsNearest) {
  const auto h = firstHit(kCube, {0.5, 0.5, -2}, {0, 0, 1});
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->t, 2.0);
  EXPECT_TRUE(h->frontFacing);
  EXPECT_EQ(h->point, Vec3(0.5, 0.5, 0));
  EXPECT_LT(h->triangle, 2u);  // a -z face triangle
  EXPECT_FALSE(firstHit(kCube, {0.5, 0.5, -2}, {0, 0, -1}));
  const auto culled = firstHit(kCube, {0.5, 0.5, 0.5}, {0, 0, 1}, Culling::BackFaces);
  EXPECT_FALSE(culled);  // from inside only back faces are ahead
}

TEST(collisionMeshRayCast, AllHitsSortedAndDistinct) {
  const auto hits = allHits(kCube, {0.5, 0.25, -2}, {0, 0, 1});
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_DOUBLE_EQ(hits[0].t, 2.0);
  EXPECT_DOUBLE_EQ(hits[1].t, 3.0);
  EXPECT_TRUE(hits[0].frontFacing);
  EXPECT_FALSE(hits[1].frontFacing);
}

TEST(collisionMeshRayCast, ParityFromOutsideIsEvenFromInsideOdd) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), inside(0.05, 0.95), outside(-3.0, 4.0);
  int crossingRays = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 dir{unit(rng), unit(rng), unit(rng)};
    if (norm(dir) < 1e-3) continue;
    const Vec3 in{inside(rng), inside(rng), inside(rng)};
    EXPECT_EQ(allHits(kCube, in, dir).size() % 2, 1u) << "inside sample " << i;
    Vec3 out{outside(rng), outside(rng), outside(rng)};
    if (out.x >= 0 && out.x <= 1 && out.y >= 0 && out.y <= 1 && out.z >= 0 && out.z <= 1) continue;
    EXPECT_EQ(allHits(kCube, out, dir).size() % 2, 0u) << "outside sample " << i;
    // Aimed at a point inside: must enter and leave.
    const std::size_t n = allHits(kCube, out, Vec3{inside(rng), inside(rng), inside(rng)} - out).size();
    EXPECT_EQ(n, 2u) << "aimed outside sample " << i;
    crossingRays += n > 0;
  }
  EXPECT_GT(crossingRays, 1000);  // the outside samples did exercise real crossings
}

TEST(collisionMeshRayCast, RaysThroughEdgesAndVerticesKeepParity) {
  // Across the diagonal: enters through the -x/-y edge, leaves through the +x/+y edge.
  EXPECT_EQ(allHits(kCube, {-1, -1, 0.5}, {1, 1, 0}).size(), 2u);
  // Through two opposite corners: each corner is shared by six triangles facing the same way.
  EXPECT_EQ(allHits(kCube, {-1, -1, -1}, {1, 1, 1}).size(), 2u);
  // From the centre through a corner: one crossing.
  EXPECT_EQ(allHits(kCube, {0.5, 0.5, 0.5}, {1, 1, 1}).size(), 1u);
  // From the centre through an edge midpoint.
  EXPECT_EQ(allHits(kCube, {0.5, 0.5, 0.5}, {0, 1, 1}).size(), 1u);
  // Grazing the -y/+z edge from outside: enters and leaves at the same point, stays even.
  EXPECT_EQ(allHits(kCube, {0.5, -1, 0}, {0, 1, 1}).size() % 2, 0u);
  // Lying in the -y face's plane: coplanar triangles are skipped, the -x and +x faces count.
  EXPECT_EQ(allHits(kCube, {-1, 0, 0.5}, {1, 0, 0}).size(), 2u);
}

namespace {
// A UV sphere (lat-long grid, poles as triangle fans): many small triangles at every angle.
TriangleMesh uvSphere(double radius, int rings, int segments) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  m.vertices.push_back({0, 0, radius});
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = pi * r / rings, phi = 2 * pi * s / segments;
      m.vertices.push_back({radius * std::sin(theta) * std::cos(phi), radius * std::sin(theta) * std::sin(phi),
                            radius * std::cos(theta)});
    }
  m.vertices.push_back({0, 0, -radius});
  const auto at = [&](int r, int s) { return std::uint32_t(1 + (r - 1) * segments + (s % segments)); };
  const std::uint32_t south = std::uint32_t(m.vertices.size() - 1);
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, at(1, s), at(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      m.triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      m.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
    m.triangles.push_back({at(rings - 1, s), south, at(rings - 1, s + 1)});
  }
  return m;
}
}  // namespace

// The in-place cast over a bone state (a click in the view) finds what the cast over its mesh finds, hit for hit,
// on a state with holes in its slots (removed triangles); its `triangle` is the slot.
TEST(collisionMeshRayCast, FirstHitOnABoneStateIsTheMeshCastsHit) {
  const BoneState full = BoneState::fromMesh(uvSphere(10, 24, 48));
  MeshDelta holes;
  for (std::uint32_t slot = 3; slot < full.triangleSlotCount(); slot += 7) holes.removedTriangles.push_back(slot);
  const BoneState bone = full.applyDelta(holes);
  std::vector<std::uint32_t> liveSlots;
  bone.forEachLiveTriangle([&](std::uint32_t slot, const Triangle&) { liveSlots.push_back(slot); });
  const TriangleMesh mesh = bone.toMesh();
  ASSERT_EQ(mesh.triangles.size(), liveSlots.size());
  std::mt19937 rng(55);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, misses = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 origin{15 * u(rng), 15 * u(rng), 15 * u(rng)};
    const Vec3 dir = normalized(Vec3{4 * u(rng), 4 * u(rng), 4 * u(rng)} - origin);
    for (Culling culling : {Culling::None, Culling::BackFaces}) {
      const std::optional<MeshHit> fromMesh = firstHit(mesh, origin, dir, culling);
      const std::optional<MeshHit> inPlace = firstHit(bone, origin, dir, culling);
      ASSERT_EQ(fromMesh.has_value(), inPlace.has_value()) << i;
      if (!fromMesh) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_EQ(inPlace->t, fromMesh->t) << i;
      EXPECT_EQ(inPlace->point, fromMesh->point) << i;
      EXPECT_EQ(inPlace->triangle, liveSlots[fromMesh->triangle]) << i;
    }
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 100);  // rays through the holes and past the sphere
  EXPECT_THROW(firstHit(bone, {0, 0, 0}, {0, 0, 0}), std::invalid_argument);
}
