#include <gtest/gtest.h>

#include <random>

#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/collision/RayTriangle.h"

using namespace reamsim;

namespace {
// Unit right triangle in z = 0, counter-clockwise seen from +Z (normal +Z).
const Vec3 A{0, 0, 0}, B{1, 0, 0}, C{0, 1, 0};
const Vec3 kDown{0, 0, -1};
std::optional<RayHit> castDown(double x, double y, Culling c = Culling::None) {
  return intersectRayTriangle({x, y, 1}, kDown, A, B, C, c);
}
}  // namespace

TEST(collisionRayTriangle, HitInside) {
  const auto h = castDown(0.25, 0.5);
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->t, 1.0);
  EXPECT_DOUBLE_EQ(h->u, 0.25);
  EXPECT_DOUBLE_EQ(h->v, 0.5);
  EXPECT_TRUE(h->frontFacing);
}

TEST(collisionRayTriangle, TIsInUnitsOfDirectionLength) {
  const auto h = intersectRayTriangle({0.2, 0.2, 4}, {0, 0, -2}, A, B, C);
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->t, 2.0);
}

TEST(collisionRayTriangle, Miss) {
  EXPECT_FALSE(castDown(2, 2));
  EXPECT_FALSE(castDown(0.6, 0.6));  // beyond the hypotenuse
  EXPECT_FALSE(castDown(-0.1, 0.5));
  EXPECT_FALSE(castDown(0.5, -1e-6));  // clearly outside, well beyond the barycentric epsilon
}

TEST(collisionRayTriangle, ThroughEdgesIsAHit) {
  for (auto [x, y] : {std::pair{0.5, 0.0}, std::pair{0.0, 0.5}, std::pair{0.5, 0.5}, std::pair{0.3, 0.7}}) {
    const auto h = castDown(x, y);
    ASSERT_TRUE(h) << x << "," << y;
    EXPECT_DOUBLE_EQ(h->t, 1.0);
  }
}

TEST(collisionRayTriangle, ThroughVerticesIsAHit) {
  for (const Vec3& p : {A, B, C}) {
    const auto h = castDown(p.x, p.y);
    ASSERT_TRUE(h) << p.x << "," << p.y;
    EXPECT_DOUBLE_EQ(h->t, 1.0);
  }
}

TEST(collisionRayTriangle, ParallelAndCoplanarMiss) {
  EXPECT_FALSE(intersectRayTriangle({0.25, 0.25, 1}, {1, 0, 0}, A, B, C));   // parallel, above the plane
  EXPECT_FALSE(intersectRayTriangle({-1, 0.25, 0}, {1, 0, 0}, A, B, C));     // in the plane, across it
  EXPECT_FALSE(intersectRayTriangle({0.1, 0.1, 0}, {1, 1, 0}, A, B, C));     // in the plane, from inside
  EXPECT_FALSE(intersectRayTriangle({0.2, 0.2, 1}, kDown, A, B, A * 0.5 + B * 0.5));  // zero-area triangle
}

TEST(collisionRayTriangle, BackFaceCulling) {
  const Vec3 from{0.25, 0.25, -1}, up{0, 0, 1};
  const auto h = intersectRayTriangle(from, up, A, B, C, Culling::None);
  ASSERT_TRUE(h);
  EXPECT_FALSE(h->frontFacing);
  EXPECT_DOUBLE_EQ(h->t, 1.0);
  EXPECT_FALSE(intersectRayTriangle(from, up, A, B, C, Culling::BackFaces));
  EXPECT_TRUE(castDown(0.25, 0.25, Culling::BackFaces));  // front face still hits
}

TEST(collisionRayTriangle, BehindOriginMissesAndOriginOnSurfaceHitsAtZero) {
  EXPECT_FALSE(intersectRayTriangle({0.25, 0.25, -1}, kDown, A, B, C));
  const auto h = intersectRayTriangle({0.25, 0.25, 0}, kDown, A, B, C);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->t, 0.0);
}

TEST(collisionRayTriangle, SharedEdgeIsNeverMissedAndCountedOnce) {
  // Two triangles with awkward coordinates sharing the edge p-q; rays aimed at points on that edge
  // (rounded to doubles) must hit at least one triangle, and allHits must report one crossing.
  TriangleMesh quad;
  quad.vertices = {{0.1, 0.3, 0.7}, {10.3, 1.7, 2.9}, {3.3, -7.1, 1.1}, {5.9, 8.3, 0.3}};
  quad.triangles = {{0, 1, 2}, {0, 3, 1}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> s(0.0, 1.0), d(-0.3, 0.3);
  const Vec3 p = quad.vertices[0], q = quad.vertices[1];
  for (int i = 0; i < 2000; ++i) {
    const Vec3 target = p + (q - p) * s(rng);
    const Vec3 dir = normalized(Vec3{d(rng), d(rng), 1.0});
    const Vec3 origin = target - dir * 5.0;
    const auto hits = allHits(quad, origin, dir);
    ASSERT_EQ(hits.size(), 1u) << "sample " << i;
    EXPECT_NEAR(hits[0].t, 5.0, 1e-9);
  }
}
