#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "MeshChecks.h"
#include "TestSpecs.h"
#include "reamsim/tools/MeshClosure.h"
#include "reamsim/tools/ReamerGeometry.h"

using namespace reamsim;

namespace {
constexpr double kPi = 3.14159265358979323846;

using test::flat;
using test::spherical;
double relativeVolumeError(const ReamerSpec& s) {
  const double ideal = idealCuttingVolume(s);
  return std::abs(signedVolume(buildCuttingSolid(s)) - ideal) / ideal;
}
}  // namespace

TEST(toolsReamerGeometry, CapHeightClosedForm) {
  const ReamerSpec s = spherical(44, 35);
  EXPECT_NEAR(capHeight(s), 35 - std::sqrt(35.0 * 35 - 22.0 * 22), 1e-12);
  EXPECT_EQ(capHeight(flat(40)), 0.0);
}

TEST(toolsReamerGeometry, IdealVolumeClosedForm) {
  const ReamerSpec s = spherical(44, 35, 12);
  const double h = capHeight(s);
  EXPECT_NEAR(idealCuttingVolume(s), kPi * 22 * 22 * 12 + kPi * h * h * (3 * 35 - h) / 3, 1e-9);
  EXPECT_NEAR(idealCuttingVolume(flat(30, 10)), kPi * 15 * 15 * 10, 1e-9);
  // Hemisphere (D/2 == R): cap volume is 2/3 pi R^3.
  EXPECT_NEAR(idealCuttingVolume(spherical(40, 20, 0)), 2.0 / 3.0 * kPi * 8000, 1e-9);
}

TEST(toolsReamerGeometry, SphericalSolidIsClosedOutwardAndBounded) {
  const ReamerSpec s = spherical(44, 35, 12, 64, 10);
  const TriangleMesh m = buildCuttingSolid(s);
  EXPECT_TRUE(test::isClosedOriented(m));
  EXPECT_TRUE(checkClosure(m).closed()) << checkClosure(m).describe();
  EXPECT_GT(signedVolume(m), 0);
  const Bounds b = computeBounds(m);
  EXPECT_NEAR(b.max.z, 0.0, 1e-12);
  EXPECT_NEAR(b.min.z, -capHeight(s) - 12, 1e-12);
  EXPECT_NEAR(b.max.x, 22.0, 1e-12);  // vertex at phi = 0 lies on the rim circle
  // The face's vertices, the body's back ring and its centre; a fan and zipped bands on the face (two
  // triangles per face vertex but the apex, less the rim's), the body band and the back fan.
  const std::size_t faceVertices = cuttingFaceVertices(s).size();
  EXPECT_EQ(m.vertexCount(), faceVertices + 64 + 1);
  EXPECT_EQ(m.triangleCount(), 2 * (faceVertices - 1) - 64 + 2 * 64 + 64);
}

// A spherical cap's rings carry vertices in proportion to their radius (the rim all `segments`, at least
// six), so the face's facets keep about the rim's size up to the apex: no needles there.
TEST(toolsReamerGeometry, FaceRingsFollowTheRadiusSoFacetsStayWellShaped) {
  for (const ReamerSpec& s : {spherical(36, 30, 12, 96, 12), spherical(44, 35, 12, 64, 10), spherical(50, 25, 0, 32, 6)}) {
    const auto face = cuttingFaceVertices(s);
    const TriangleMesh m = buildCuttingSolid(s);
    std::size_t rim = 0;
    for (const Vec3& p : face) rim += std::abs(std::hypot(p.x, p.y) - s.diameterMm / 2) < 1e-9;
    EXPECT_EQ(rim, static_cast<std::size_t>(s.segments));
    EXPECT_LT(face.size(), static_cast<std::size_t>(1 + s.segments * s.rings));
    double smallest = 180;
    for (const Triangle& t : m.triangles)
      if (t[0] < face.size() && t[1] < face.size() && t[2] < face.size())
        smallest = std::min(smallest, smallestAngle(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]) * 180 / kPi);
    EXPECT_GT(smallest, 15.0) << s.segments << " x " << s.rings;
    // Still convex (a moved reamer is swept by hulls): every vertex on or behind every facet's plane.
    for (const Triangle& t : m.triangles) {
      const Vec3 a = m.vertices[t[0]], n = normalized(cross(m.vertices[t[1]] - a, m.vertices[t[2]] - a));
      for (const Vec3& p : m.vertices) ASSERT_LE(dot(n, p - a), 1e-9 * 50) << s.segments << " x " << s.rings;
    }
  }
}

TEST(toolsReamerGeometry, FaceVerticesLieOnTheSphereAndStartTheSolid) {
  const ReamerSpec s = spherical(36, 30, 12, 32, 6);
  const auto face = cuttingFaceVertices(s);
  ASSERT_GT(face.size(), static_cast<std::size_t>(1 + 32));
  EXPECT_EQ(face.front(), Vec3(0, 0, 0));
  const TriangleMesh m = buildCuttingSolid(s);
  for (std::size_t i = 0; i < face.size(); ++i) {
    EXPECT_EQ(face[i], m.vertices[i]);
    EXPECT_NEAR(norm(face[i] - Vec3(0, 0, -30)), 30.0, 1e-9);
    EXPECT_LE(std::hypot(face[i].x, face[i].y), 18.0 + 1e-12);
    EXPECT_LE(face[i].z, 0.0);
    EXPECT_GE(face[i].z, -capHeight(s) - 1e-12);
  }
}

TEST(toolsReamerGeometry, FaceTrianglesPointForward) {
  // The cutting face is the front of the solid: its facets' normals have a positive Z component.
  const ReamerSpec s = spherical(40, 32, 12, 24, 4);
  const TriangleMesh m = buildCuttingSolid(s);
  const std::size_t faceVertices = cuttingFaceVertices(s).size();
  std::size_t faceTriangles = 0;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const Triangle& t = m.triangles[i];
    if (t[0] >= faceVertices || t[1] >= faceVertices || t[2] >= faceVertices) continue;
    ++faceTriangles;
    const Vec3 n = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    EXPECT_GT(n.z, 0) << "triangle " << i;
  }
  EXPECT_EQ(faceTriangles, 2 * (faceVertices - 1) - 24);  // fan and zipped bands
}

TEST(toolsReamerGeometry, FlatReamer) {
  const ReamerSpec s = flat(30, 10, 48, 5);
  const TriangleMesh m = buildCuttingSolid(s);
  EXPECT_TRUE(test::isClosedOriented(m));
  EXPECT_GT(signedVolume(m), 0);
  const auto face = cuttingFaceVertices(s);
  ASSERT_GT(face.size(), static_cast<std::size_t>(1 + 48));
  for (const Vec3& p : face) {
    EXPECT_EQ(p.z, 0.0);
    EXPECT_LE(std::hypot(p.x, p.y), 15.0 + 1e-12);
  }
  const Bounds b = computeBounds(m);
  EXPECT_EQ(b.max.z, 0.0);
  EXPECT_EQ(b.min.z, -10.0);
  // The disc's interior rings do not change the volume: only the inscribed rim polygon matters.
  const double polygonArea = 0.5 * 48 * 15 * 15 * std::sin(2 * kPi / 48);
  EXPECT_NEAR(signedVolume(m), polygonArea * 10, 1e-9);
}

TEST(toolsReamerGeometry, CapWithoutBodyIsClosed) {
  const TriangleMesh m = buildCuttingSolid(spherical(40, 20, 0, 32, 8));  // hemisphere
  EXPECT_TRUE(test::isClosedOriented(m));
  EXPECT_GT(signedVolume(m), 0);
}

TEST(toolsReamerGeometry, VolumeErrorShrinksWithResolution) {
  for (const ReamerSpec& base : {spherical(44, 35), spherical(28, 25), spherical(56, 40), flat(42, 12)}) {
    double previous = std::numeric_limits<double>::infinity();
    for (auto [seg, rings] : {std::pair{16, 4}, std::pair{32, 8}, std::pair{64, 16}, std::pair{256, 48}}) {
      ReamerSpec s = base;
      s.segments = seg;
      s.rings = rings;
      const double err = relativeVolumeError(s);
      EXPECT_LT(err, previous) << base.diameterMm << "/" << base.sphereRadiusMm << " at " << seg << "x" << rings;
      previous = err;
    }
    EXPECT_LT(previous, 0.002) << "segments=256, rings=48";
  }
}

TEST(toolsReamerGeometry, RejectsDiameterWiderThanSphere) {
  try {
    buildCuttingSolid(spherical(60, 25));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("D/2 <= R"), std::string::npos) << e.what();
  }
  EXPECT_THROW(idealCuttingVolume(spherical(60, 25)), std::invalid_argument);
  EXPECT_THROW(cuttingFaceVertices(spherical(60, 25)), std::invalid_argument);
  EXPECT_NO_THROW(buildCuttingSolid(spherical(50, 25)));  // D/2 == R is a hemisphere
}

TEST(toolsReamerGeometry, RejectsNonsense) {
  EXPECT_THROW(buildCuttingSolid(spherical(0, 25)), std::invalid_argument);
  EXPECT_THROW(buildCuttingSolid(spherical(40, -25)), std::invalid_argument);
  EXPECT_THROW(buildCuttingSolid(spherical(40, std::nan(""))), std::invalid_argument);
  EXPECT_THROW(buildCuttingSolid(spherical(40, 25, -1)), std::invalid_argument);
  EXPECT_THROW(buildCuttingSolid(flat(40, 0)), std::invalid_argument);
  EXPECT_THROW(buildCuttingSolid(spherical(40, 25, 10, 2, 4)), std::invalid_argument);
  EXPECT_THROW(buildCuttingSolid(spherical(40, 25, 10, 16, 0)), std::invalid_argument);
}

TEST(toolsMeshClosure, DetectsOpenAndMisorientedMeshes) {
  TriangleMesh m = buildCuttingSolid(spherical(40, 32, 10, 12, 3));
  ASSERT_TRUE(checkClosure(m).closed());
  TriangleMesh open = m;
  open.triangles.pop_back();
  EXPECT_EQ(checkClosure(open).boundaryEdges, 3u);
  TriangleMesh flipped = m;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(checkClosure(flipped).misorientedEdges, 3u);
  EXPECT_FALSE(checkClosure(flipped).closed());
  EXPECT_NE(checkClosure(flipped).describe().find("inconsistently oriented"), std::string::npos);
}
