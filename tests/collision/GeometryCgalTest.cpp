// The exact-up-to-rounding primitives against CGAL (the one CGAL unit of these tests): triangle-triangle
// intersection against CGAL's exact predicates, triangle-triangle distance against CGAL's own. Disagreements
// are allowed only within the stated tolerance (pairs closer than 1e-9 of their size count as touching).
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <CGAL/squared_distance_3.h>

#include <random>

#include "reamsim/collision/TriangleGeometry.h"

using namespace reamsim;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;

K::Triangle_3 toCgal(const Vec3 (&t)[3]) {
  return {{t[0].x, t[0].y, t[0].z}, {t[1].x, t[1].y, t[1].z}, {t[2].x, t[2].y, t[2].z}};
}
double exactDistance(const Vec3 (&a)[3], const Vec3 (&b)[3]) {
  const EK::Triangle_3 ta({a[0].x, a[0].y, a[0].z}, {a[1].x, a[1].y, a[1].z}, {a[2].x, a[2].y, a[2].z});
  const EK::Triangle_3 tb({b[0].x, b[0].y, b[0].z}, {b[1].x, b[1].y, b[1].z}, {b[2].x, b[2].y, b[2].z});
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(ta, tb)));
}

struct Pair {
  Vec3 a[3], b[3];
};

// Random pairs plus the degenerate families: shared vertex, shared edge, vertex on the other's face, crossing
// edges, coplanar overlapping and coplanar apart, parallel planes at tiny gaps.
std::vector<Pair> makePairs(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto p = [&] { return Vec3{u(rng), u(rng), u(rng)}; };
  std::vector<Pair> out;
  while (out.size() < n) {
    Pair q{{p(), p(), p()}, {p(), p(), p()}};
    const Vec3 na = cross(q.a[1] - q.a[0], q.a[2] - q.a[0]);
    switch (out.size() % 8) {
      case 1: q.b[0] = q.a[0]; break;                                       // shared vertex
      case 2: q.b[0] = q.a[0]; q.b[1] = q.a[1]; break;                      // shared edge
      case 3: q.b[0] = q.a[0] * 0.2 + q.a[1] * 0.3 + q.a[2] * 0.5; break;  // vertex on the face (to rounding)
      case 4: {                                                             // coplanar, overlapping or not
        for (Vec3& v : q.b) v = q.a[0] + (q.a[1] - q.a[0]) * u(rng) * 1.5 + (q.a[2] - q.a[0]) * u(rng) * 1.5;
        break;
      }
      case 5: {                                                             // parallel plane at a tiny gap
        const double gap = std::pow(10.0, -3 - 10 * (u(rng) + 1) / 2);    // 1e-3 .. 1e-13
        for (int k = 0; k < 3; ++k) q.b[k] = q.a[k] + normalized(na) * gap + (q.a[(k + 1) % 3] - q.a[k]) * 0.3;
        break;
      }
      case 6: {                                                             // an edge crossing the other's edge
        const Vec3 m = (q.a[0] + q.a[1]) * 0.5;
        q.b[0] = m + normalized(na) * 0.5;
        q.b[1] = m - normalized(na) * 0.5;
        break;
      }
      default: break;
    }
    out.push_back(q);
  }
  return out;
}

bool degenerate(const Vec3 (&t)[3]) { return squaredNorm(cross(t[1] - t[0], t[2] - t[0])) < 1e-20; }

}  // namespace

TEST(collisionGeometry, TriangleIntersectionAgreesWithCgalExactPredicates) {
  std::size_t checked = 0, intersecting = 0, withinTolerance = 0;
  for (const Pair& q : makePairs(20000, 51)) {
    if (degenerate(q.a) || degenerate(q.b)) continue;
    const bool exact = CGAL::do_intersect(toCgal(q.a), toCgal(q.b));
    const bool ours = trianglesIntersect(q.a[0], q.a[1], q.a[2], q.b[0], q.b[1], q.b[2]);
    ++checked;
    intersecting += exact;
    if (exact != ours) {
      // Allowed only for pairs that touch within the tolerance: apart by less than 1e-9 of their size.
      const double d = exactDistance(q.a, q.b);
      EXPECT_TRUE(ours && d < 1e-9) << "ours " << ours << " exact " << exact << " distance " << d;
      ++withinTolerance;
    }
  }
  EXPECT_GE(checked, 19000u);
  EXPECT_GT(intersecting, 5000u);
  // Only near-touching pairs (the parallel planes closer than 1e-9, vertices on a face up to rounding) differ.
  EXPECT_GT(withinTolerance, 0u);
  EXPECT_LT(withinTolerance, checked / 4);
}

TEST(collisionGeometry, TriangleDistanceAgreesWithCgal) {
  std::size_t checked = 0;
  for (const Pair& q : makePairs(12000, 52)) {
    if (degenerate(q.a) || degenerate(q.b)) continue;
    const double reference = std::sqrt(CGAL::squared_distance(toCgal(q.a), toCgal(q.b)));
    const ClosestPair cp = closestTriangleTriangle(q.a[0], q.a[1], q.a[2], q.b[0], q.b[1], q.b[2]);
    const double d = std::sqrt(cp.squaredDistance);
    EXPECT_NEAR(d, reference, 1e-9 * (1 + reference));
    // The pair realises the distance and lies on the triangles.
    EXPECT_NEAR(norm(cp.onA - cp.onB), d, 1e-9);
    EXPECT_LT(norm(cp.onA - closestPointOnTriangle(cp.onA, q.a[0], q.a[1], q.a[2])), 1e-9);
    EXPECT_LT(norm(cp.onB - closestPointOnTriangle(cp.onB, q.b[0], q.b[1], q.b[2])), 1e-9);
    if (::testing::Test::HasFailure()) return;
    ++checked;
  }
  EXPECT_GE(checked, 11000u);
}
