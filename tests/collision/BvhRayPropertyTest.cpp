// Query 4: BVH ray casts against the brute-force Moeller-Trumbore casts (MeshRayCast.h), hit for hit.
// Same per-triangle test, so the tolerance is zero: identical t, triangle, facing and crossing list.
#include <gtest/gtest.h>

#include <random>

#include "CollisionFixtures.h"
#include "reamsim/collision/BvhRayCast.h"
#include "reamsim/collision/MeshRayCast.h"

using namespace reamsim;

namespace {

struct RayCase {
  Vec3 origin, dir;
};

// Mix of random rays and the degenerate ones: through vertices, through points on edges, at face points,
// with exactly zero direction components.
std::vector<RayCase> makeRays(const TriangleMesh& m, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Bounds b = computeBounds(m).expanded(0.2 * computeBounds(m).diagonal());
  auto randomPoint = [&] {
    return Vec3{b.min.x + u(rng) * (b.max.x - b.min.x), b.min.y + u(rng) * (b.max.y - b.min.y),
                b.min.z + u(rng) * (b.max.z - b.min.z)};
  };
  auto randomDir = [&] {
    for (;;) {
      const Vec3 d{2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1};
      if (squaredNorm(d) > 0.01 && squaredNorm(d) <= 1) return d;
    }
  };
  std::vector<RayCase> rays;
  std::uniform_int_distribution<std::size_t> tri(0, m.triangles.size() - 1);
  while (rays.size() < count) {
    const Vec3 o = randomPoint();
    const Triangle& t = m.triangles[tri(rng)];
    const Vec3 a = m.vertices[t[0]], c = m.vertices[t[1]];
    switch (rays.size() % 6) {
      case 0: rays.push_back({o, randomDir()}); break;
      case 1: rays.push_back({o, a - o}); break;                               // through a vertex
      case 2: rays.push_back({o, a + (c - a) * u(rng) - o}); break;            // through an edge
      case 3: rays.push_back({o, a + (c - a) * 0.5 - o}); break;               // through an edge midpoint
      case 4: rays.push_back({test::sampleSurface(m, rng).point, randomDir()}); break;  // from the surface
      default: {
        Vec3 d{0, 0, 0};
        d[static_cast<int>(rays.size() / 6 % 3)] = u(rng) < 0.5 ? -1 : 1;      // axis-aligned: zero components
        rays.push_back({a + Vec3{1e-3, -2e-3, 0.5e-3} * (u(rng) - 0.5), d});
      }
    }
  }
  return rays;
}

void expectSameHit(const std::optional<MeshHit>& brute, const std::optional<MeshHit>& bvh, const RayCase& r) {
  ASSERT_EQ(brute.has_value(), bvh.has_value()) << "origin " << r.origin.x << "," << r.origin.y << "," << r.origin.z;
  if (!brute) return;
  EXPECT_EQ(brute->t, bvh->t);
  EXPECT_EQ(brute->triangle, bvh->triangle);
  EXPECT_EQ(brute->frontFacing, bvh->frontFacing);
}

void expectSameCrossings(const std::vector<MeshHit>& brute, const std::vector<MeshHit>& bvh) {
  ASSERT_EQ(brute.size(), bvh.size());
  for (std::size_t i = 0; i < brute.size(); ++i) {
    EXPECT_EQ(brute[i].t, bvh[i].t);
    EXPECT_EQ(brute[i].triangle, bvh[i].triangle);
    EXPECT_EQ(brute[i].frontFacing, bvh[i].frontFacing);
  }
}

// Returns the number of rays checked (each in the four variants).
std::size_t checkMesh(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed) {
  const TriangleBvh bvh = TriangleBvh::fromMesh(mesh);
  EXPECT_EQ(bvh.validate(), "");
  std::size_t hits = 0;
  for (const RayCase& r : makeRays(mesh, count, seed)) {
    for (Culling c : {Culling::None, Culling::BackFaces}) {
      const auto bf = firstHit(mesh, r.origin, r.dir, c);
      expectSameHit(bf, firstHit(bvh, r.origin, r.dir, c), r);
      expectSameCrossings(allHits(mesh, r.origin, r.dir, c), allHits(bvh, r.origin, r.dir, c));
      hits += bf.has_value();
    }
    if (::testing::Test::HasFailure()) return 0;
  }
  EXPECT_GT(hits, count / 4);  // the rays do meet the surface
  return count;
}

}  // namespace

TEST(collisionBvhRays, MatchBruteForceOnSphere) { EXPECT_EQ(checkMesh(test::icosphere(3, 20, {1, 2, 3}), 3400, 1), 3400u); }

TEST(collisionBvhRays, MatchBruteForceOnBlock) {
  EXPECT_EQ(checkMesh(test::block({-30, -30, 0}, {30, 30, 20}, 6), 3400, 2), 3400u);
}

TEST(collisionBvhRays, MatchBruteForceOnBundledScapula) {
  EXPECT_EQ(checkMesh(test::bundledScapula(), 3400, 3), 3400u);
}

// Rays lying in a face plane, along edges, and parallel to faces at tiny offsets.
TEST(collisionBvhRays, CoplanarAndParallelRaysMatchBruteForce) {
  const TriangleMesh m = test::block({0, 0, 0}, {10, 10, 10}, 4);
  const TriangleBvh bvh = TriangleBvh::fromMesh(m);
  std::vector<RayCase> rays;
  for (double off : {0.0, 1e-12, -1e-12, 1e-6, 2.5}) {
    rays.push_back({{-5, 5, 10 + off}, {1, 0, 0}});        // in / just off the top face plane
    rays.push_back({{-5, -5, 10 + off}, {1, 1, 0}});       // diagonal in the plane, through vertices
    rays.push_back({{-5, 0 + off, 10}, {1, 0, 0}});        // along an edge of the block
    rays.push_back({{5, 5, 20}, {off, 0, -1}});            // straight down onto a grid vertex
    rays.push_back({{2.5, 2.5 + off, 20}, {0, 0, -1}});    // onto an interior grid edge
  }
  for (const RayCase& r : rays)
    for (Culling c : {Culling::None, Culling::BackFaces}) {
      expectSameHit(firstHit(m, r.origin, r.dir, c), firstHit(bvh, r.origin, r.dir, c), r);
      expectSameCrossings(allHits(m, r.origin, r.dir, c), allHits(bvh, r.origin, r.dir, c));
    }
  // A ray down onto a shared grid vertex crosses the block once on the way in and once on the way out.
  EXPECT_EQ(allHits(bvh, {5, 5, 20}, {0, 0, -1}).size(), 2u);
  EXPECT_TRUE(insideClosedSurface(bvh, {3.3, 4.4, 5.5}));
  EXPECT_FALSE(insideClosedSurface(bvh, {13.3, 4.4, 5.5}));
}

TEST(collisionBvhRays, EmptyTreeHasNoHits) {
  const TriangleBvh empty;
  EXPECT_FALSE(firstHit(empty, {0, 0, 0}, {0, 0, 1}).has_value());
  EXPECT_TRUE(allHits(empty, {0, 0, 0}, {0, 0, 1}).empty());
}
