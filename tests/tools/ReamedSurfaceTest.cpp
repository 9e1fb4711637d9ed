// measureReamedSurface against surfaces whose answer is known: a fine spherical cavity exactly where the
// ideal face is (seated over the part of the cap it spans, standoff ~0), the same seen from a pose moved
// along the axis (the standoff follows the move), a ball instead of a cavity (its faces look away from the
// reamer: nothing counted), a flat floor under a flat reamer; and the facet sag of the preset meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "TestSpecs.h"
#include "reamsim/tools/ReamedSurface.h"
#include "reamsim/tools/ReamerGeometry.h"

using namespace reamsim;

namespace {
constexpr double kPi = 3.14159265358979323846;

ReamerSpec cap(double d, double r, int segments = 96, int rings = 12) { return test::spherical(d, r, 12, segments, rings); }

// The zone of the sphere of radius r about c within polar angle maxPolar of its lowest point c - (0, 0, r),
// a fine UV grid, its faces turned towards c (a cavity's surface: the bone's outward normal looks into the
// cavity) unless `outward` (a ball).
TriangleMesh sphereZone(const Vec3& c, double r, double maxPolar, int around, int down, bool outward = false) {
  TriangleMesh m;
  m.vertices.push_back(c - Vec3{0, 0, r});
  for (int i = 1; i <= down; ++i) {
    const double th = maxPolar * i / down;
    for (int j = 0; j < around; ++j) {
      const double ph = 2 * kPi * j / around;
      m.vertices.push_back(c + Vec3{r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), -r * std::cos(th)});
    }
  }
  auto at = [&](int ring, int j) { return std::uint32_t(1 + (ring - 1) * around + (j % around)); };
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t d) {
    const Vec3 n = cross(m.vertices[b] - m.vertices[a], m.vertices[d] - m.vertices[a]);
    const bool away = dot(n, m.vertices[a] - c) > 0;
    if (away == outward) m.triangles.push_back({a, b, d});
    else m.triangles.push_back({a, d, b});
  };
  for (int j = 0; j < around; ++j) add(0, at(1, j), at(1, j + 1));
  for (int i = 1; i < down; ++i)
    for (int j = 0; j < around; ++j) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

// The reamer fed along -Z with its tip at the origin: the ideal sphere's centre is (0, 0, r).
const Pose kDownAtOrigin{{0, 0, 0}, {0, 0, -1}, 0};
}  // namespace

TEST(toolsReamedSurface, ACavityOnTheIdealSphereIsSeatedOverTheZoneItSpans) {
  const ReamerSpec s = cap(36, 30);
  const double h = capHeight(s), depth = 3.0;
  // A cavity `depth` deep: the zone of polar angle acos((r - depth) / r) about the apex.
  const TriangleMesh cavity = sphereZone({0, 0, 30}, 30, std::acos((30 - depth) / 30), 720, 120);
  const ReamedSurfaceReport r = measureReamedSurface(cavity, s, kDownAtOrigin);
  EXPECT_NEAR(r.faceAreaMm2, 2 * kPi * 30 * h, 1e-9);
  EXPECT_GT(r.faces, 0u);
  EXPECT_NEAR(r.seatedFraction, depth / h, 1e-3) << "the zone's area 2 pi r depth over the cap's 2 pi r h";
  // A fine grid's corners lie on the sphere and its centroids a hair inside: standoff 0 to ~1e-4 mm.
  EXPECT_GE(r.standoffMinMm, -1e-9);
  EXPECT_LT(r.standoffMaxMm, 1e-3);
  EXPECT_LT(r.standoffRmsMm, 1e-3);
  EXPECT_GT(r.facetSagMm, 0.0);
}

TEST(toolsReamedSurface, TheStandoffFollowsAPoseMovedAlongTheAxis) {
  const ReamerSpec s = cap(36, 30);
  const TriangleMesh cavity = sphereZone({0, 0, 30}, 30, std::acos(24.0 / 30), 720, 120);  // the whole cap
  const double d = 0.04;
  // The ideal reamer 0.04 mm deeper: bone is left inside it, by d at the apex and d cos(polar) further out.
  const ReamedSurfaceReport deeper = measureReamedSurface(cavity, s, Pose{{0, 0, -d}, {0, 0, -1}, 0}, 0.1);
  // Seen from 0.04 mm deeper, the zone's last ring of faces lies behind the cap's base: not quite all of it.
  EXPECT_NEAR(deeper.seatedFraction, 1.0, 0.01);
  EXPECT_NEAR(deeper.standoffMaxMm, d, 2e-4);
  EXPECT_NEAR(deeper.standoffMinMm, d * 24.0 / 30, 2e-3);
  // Shallower: the bone lies beyond the ideal face (cut too deep for this pose).
  const ReamedSurfaceReport shallower = measureReamedSurface(cavity, s, Pose{{0, 0, d}, {0, 0, -1}, 0}, 0.1);
  EXPECT_NEAR(shallower.standoffMinMm, -d, 2e-4);
  // Beyond the band nothing is counted.
  EXPECT_EQ(measureReamedSurface(cavity, s, Pose{{0, 0, -0.5}, {0, 0, -1}, 0}, 0.1).faces, 0u);
}

// The cavity's wall just behind the rim, where the body cut it: as close to the sphere as the face (its
// standoff is within the band for the first few hundredths of a millimetre) but not part of the face.
TEST(toolsReamedSurface, TheWallBehindTheRimIsNotTheFace) {
  const ReamerSpec s = cap(36, 30);
  const double h = capHeight(s), rho = 17.995;
  const Pose up{{0, 0, 0}, {0, 0, 1}, 0};  // reamer frame = bone frame up to a turn about z
  TriangleMesh wall;
  const int around = 720;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < around; ++j) {
      const double ph = 2 * kPi * j / around, z = k == 0 ? -h - 0.03 : -h + 0.004;
      wall.vertices.push_back({rho * std::cos(ph), rho * std::sin(ph), z});
    }
  for (int j = 0; j < around; ++j) {  // normals towards the axis: the wall faces the cavity
    const std::uint32_t a = std::uint32_t(j), b = std::uint32_t((j + 1) % around);
    wall.triangles.push_back({a, a + around, b});
    wall.triangles.push_back({b, a + around, b + around});
  }
  ASSERT_GT(dot(cross(wall.vertices[around] - wall.vertices[0], wall.vertices[1] - wall.vertices[0]), Vec3{-1, 0, 0}), 0);
  EXPECT_EQ(measureReamedSurface(wall, s, up).faces, 0u);
}

TEST(toolsReamedSurface, ABallIsNotACavity) {
  const TriangleMesh ball = sphereZone({0, 0, 30}, 30, std::acos(24.0 / 30), 360, 60, /*outward=*/true);
  EXPECT_EQ(measureReamedSurface(ball, cap(36, 30), kDownAtOrigin).faces, 0u);
}

TEST(toolsReamedSurface, AFlatFloorUnderAFlatReamer) {
  const ReamerSpec s = test::flat(20);
  // A 40 mm square floor at z = -2 facing +Z (the reamer comes from above, fed along -Z).
  TriangleMesh grid;
  const int n = 80;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) grid.vertices.push_back({-20 + 40.0 * i / n, -20 + 40.0 * j / n, -2});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = std::uint32_t(i * (n + 1) + j), b = a + std::uint32_t(n + 1);
      grid.triangles.push_back({a, b, b + 1});
      grid.triangles.push_back({a, b + 1, a + 1});
    }
  const ReamedSurfaceReport r = measureReamedSurface(grid, s, Pose{{0, 0, -2}, {0, 0, -1}, 0});
  EXPECT_NEAR(r.faceAreaMm2, kPi * 100, 1e-9);
  EXPECT_NEAR(r.seatedFraction, 1.0, 0.02);  // the grid's cells along the rim, counted by their centroids
  EXPECT_NEAR(r.standoffMinMm, 0.0, 1e-12);
  EXPECT_NEAR(r.standoffMaxMm, 0.0, 1e-12);
  EXPECT_EQ(r.facetSagMm, 0.0);
  // Facing away (the floor seen from below): nothing counted.
  EXPECT_EQ(measureReamedSurface(grid, s, Pose{{0, 0, -2}, {0, 0, 1}, 0}).faces, 0u);
}

TEST(toolsReamedSurface, FacetSagShrinksWithTheResolution) {
  const TriangleMesh none;
  const double coarse = measureReamedSurface(none, cap(36, 30, 96, 12), kDownAtOrigin).facetSagMm;
  const double fine = measureReamedSurface(none, cap(36, 30, 256, 48), kDownAtOrigin).facetSagMm;
  // A facet of chord c on a sphere of radius R sags about c^2 / (8 R): ~1.2 mm chords on R 30, ~0.01 mm.
  EXPECT_GT(coarse, 0.002);
  EXPECT_LT(coarse, 0.03);
  EXPECT_LT(fine, 0.5 * coarse);
  EXPECT_THROW(measureReamedSurface(none, cap(36, 30), kDownAtOrigin, 0.0), std::invalid_argument);
  EXPECT_THROW(measureReamedSurface(none, cap(36, 10), kDownAtOrigin), std::invalid_argument);  // D/2 > R
}
