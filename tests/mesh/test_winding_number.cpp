// FastWindingNumber (the tree of clusters the remesh decides inside from outside with) against the direct
// sum over every triangle, on meshes clean and dirty, at points far, near and on the surface.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "RepairTestMeshes.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/WindingNumber.h"

namespace reamsim {
namespace {

struct Agreement {
  double maxError = 0;
  std::size_t signDisagreements = 0;  // inside (≥ 0.5) by one and not the other, where the direct sum is clear of 0.5
  std::size_t points = 0;
  double meanTerms = 0;
};

// Points spread over the mesh's box grown by a quarter, and points within `near` of the surface
// (corners and triangle middles moved a little along random directions).
Agreement compare(const TriangleMesh& mesh, double beta, std::size_t count, double near) {
  const FastWindingNumber fast(mesh);
  const Bounds b = computeBounds(mesh);
  const Vec3 grow = (b.max - b.min) * 0.25;
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(0, 1);
  Agreement a;
  std::size_t terms = 0;
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 p;
    if (i % 2 == 0) {
      for (int k = 0; k < 3; ++k) p[k] = b.min[k] - grow[k] + u(rng) * (b.max[k] - b.min[k] + 2 * grow[k]);
    } else {
      const Triangle& t = mesh.triangles[std::size_t(u(rng) * double(mesh.triangles.size())) % mesh.triangles.size()];
      const double s = u(rng), r = u(rng) * (1 - s);
      p = mesh.vertices[t[0]] + (mesh.vertices[t[1]] - mesh.vertices[t[0]]) * s +
          (mesh.vertices[t[2]] - mesh.vertices[t[0]]) * r +
          Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * (2 * near);
    }
    const double direct = windingNumber(mesh, p);
    const double tree = fast.evaluate(p, beta, &terms);
    a.maxError = std::max(a.maxError, std::abs(direct - tree));
    if (std::abs(direct - 0.5) > 0.05 && (direct >= 0.5) != (tree >= 0.5)) ++a.signDisagreements;
    ++a.points;
  }
  a.meanTerms = double(terms) / double(count);
  return a;
}

TEST(FastWindingNumber, MatchesTheDirectSumOnAClosedBox) {
  const TriangleMesh box = test::unitBox(10, 8);  // 768 triangles
  const Agreement a = compare(box, 2.0, 4000, 0.5);
  EXPECT_EQ(a.signDisagreements, 0u);
  EXPECT_LT(a.maxError, 0.05) << "mean terms " << a.meanTerms;
  EXPECT_LT(a.meanTerms, 768.0 / 3);  // far fewer terms than there are triangles (~90 measured)
}

TEST(FastWindingNumber, MatchesTheDirectSumOnDirtyMeshes) {
  // Two overlapping boxes (winding number 2 where they overlap), one with a face removed (a hole) and one
  // with flipped faces: the cases the generalized winding number is used for.
  TriangleMesh a = test::unitBox(10, 6);
  TriangleMesh b = test::translated(test::unitBox(10, 6), {4, 3, 5});
  b.triangles.erase(b.triangles.begin() + 7);
  for (std::size_t i = 0; i < a.triangles.size(); i += 5) std::swap(a.triangles[i][1], a.triangles[i][2]);
  const TriangleMesh dirty = test::merged(a, b);
  const Agreement r = compare(dirty, 2.0, 4000, 0.5);
  EXPECT_EQ(r.signDisagreements, 0u);
  EXPECT_LT(r.maxError, 0.05);
}

TEST(FastWindingNumber, MatchesTheDirectSumOnTheBundledScapula) {
  const TriangleMesh scapula = readMesh(std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_opensim.vtp").mesh;
  ASSERT_GT(scapula.triangles.size(), 1000u);
  const Agreement a = compare(scapula, 2.0, 4000, 1.0);
  EXPECT_EQ(a.signDisagreements, 0u);
  EXPECT_LT(a.maxError, 0.05) << "mean terms " << a.meanTerms;
  // A larger beta is closer to the direct sum and sums more terms.
  const Agreement tight = compare(scapula, 8.0, 4000, 1.0);
  EXPECT_LE(tight.maxError, a.maxError);
  EXPECT_LT(tight.maxError, 0.005) << "mean terms " << tight.meanTerms;
  EXPECT_GT(tight.meanTerms, a.meanTerms);
}

// The expansion itself: a curved patch (a paraboloid cap, so that its first moment is not zero) seen from
// farther and farther away, where the whole patch is one expanded cluster. With the dipole and its first
// correction right, the error left is third order: it falls ~16× per doubling of the distance; a missing or
// wrongly signed correction leaves ~8×.
TEST(FastWindingNumber, ExpansionErrorFallsAsItsOrderSays) {
  TriangleMesh cap;
  const int n = 10;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      cap.vertices.push_back({x, y, 0.3 * (x * x + y * y)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n + 1), d = c + 1;
      cap.triangles.push_back({a, b, d});
      cap.triangles.push_back({a, d, c});
    }
  const FastWindingNumber fast(cap);
  const Vec3 direction = normalized(Vec3{0.3, -0.5, 1.0});
  double error[3];
  for (int k = 0; k < 3; ++k) {
    const Vec3 p = direction * (5.0 * (1 << k));  // 5, 10, 20: beyond 2 radii of the whole cap (radius ~1.6)
    error[k] = std::abs(fast(p) - windingNumber(cap, p));
  }
  ASSERT_GT(error[0], 0.0);
  EXPECT_LT(error[1], error[0] / 11) << error[0] << " " << error[1];
  EXPECT_LT(error[2], error[1] / 11) << error[1] << " " << error[2];
}

TEST(FastWindingNumber, HandlesEmptyMeshesAndRefusesABadBeta) {
  EXPECT_EQ(FastWindingNumber(TriangleMesh{})({1, 2, 3}), 0.0);
  const FastWindingNumber unit(test::unitBox());
  EXPECT_THROW(unit.evaluate({1, 2, 3}, 0.5), std::invalid_argument);
  EXPECT_THROW(unit.evaluate({1, 2, 3}, std::nan("")), std::invalid_argument);
  // A point at the centre of a closed box is inside, one beyond it outside, whatever the tree's shape.
  const FastWindingNumber box(test::unitBox(10, 3));
  EXPECT_NEAR(box({5, 5, 5}), 1.0, 1e-6);
  EXPECT_NEAR(box({25, 5, 5}), 0.0, 1e-3);
}

}  // namespace
}  // namespace reamsim
