// The fast exact self-intersection search must agree with the Foundation's CGAL count (same rules), and
// the guarded decimation must keep a clean closed surface clean and closed.
#include <gtest/gtest.h>

#include <cmath>

#include "Phantom.h"
#include "TestUtil.h"
#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/QuadricDecimation.h"
#include "reamsim/ctimport/SelfIntersections.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Validation.h"
#include "reamsim/tools/Primitives.h"

namespace {

using namespace reamsim;

TriangleMesh join(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const std::uint32_t off = std::uint32_t(m.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Triangle t : b.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  return m;
}

// A clean isosurface mesh (a sphere pierced by a cylinder) from the import pipeline, undecimated.
TriangleMesh isosurface(double spacing, int smoothing = 0) {
  phantom::SphereAndCylinder shape;
  shape.center = {0, 0, 0};
  const phantom::Grid g = phantom::gridAround({0, 0, 0}, 24, {spacing, spacing, spacing}, phantom::rotation({1, 0, 0}, 0));
  ct::CtVolume v;
  v.dims = g.dims;
  v.spacing = g.spacing;
  v.origin = g.origin;
  v.values = phantom::sample(g, [&](const Vec3& p) { return shape.inside(p); }, 40, 1200, 2);
  v.integerValued = false;
  ct::ImportOptions o;
  o.lowerThreshold = 620;
  o.targetFaces = 0;
  o.smoothingIterations = smoothing;
  return ct::importBone(v, o).mesh;
}

TEST(SelfIntersections, AgreesWithCgalOnOverlappingBoxes) {
  const TriangleMesh m = join(buildBox({{0, 0, 0}, {10, 10, 10}}, 4), buildBox({{5, 5, 5}, {15, 15, 15}}, 3));
  const ct::SelfIntersectionResult r = ct::findSelfIntersections(m);
  EXPECT_GT(r.pairs.size(), 0u);
  EXPECT_EQ(r.pairs.size(), countSelfIntersections(m));
  // Only faces of the second box flagged: every pair still involves one of them (here: all pairs do).
  std::vector<std::uint8_t> second(m.triangles.size(), 0);
  for (std::size_t f = buildBox({{0, 0, 0}, {1, 1, 1}}, 4).triangles.size(); f < m.triangles.size(); ++f) second[f] = 1;
  EXPECT_EQ(ct::findSelfIntersections(m, 1000000, &second).pairs, r.pairs);
  // A box resting on the other: their faces overlap in one plane, which counts, as in CGAL.
  const TriangleMesh touching = join(buildBox({{0, 0, 0}, {10, 10, 10}}, 2), buildBox({{10, 2, 2}, {20, 8, 8}}, 2));
  EXPECT_EQ(ct::findSelfIntersections(touching).pairs.size(), countSelfIntersections(touching));
}

TEST(SelfIntersections, NeighbourCasesFollowCgalRules) {
  // Two faces sharing an edge, folded flat onto each other (coplanar overlap): an intersection.
  TriangleMesh fold;
  fold.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 0.5, 0}};
  fold.triangles = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_EQ(ct::findSelfIntersections(fold).pairs.size(), 1u);
  fold.vertices[3] = {0.5, -0.5, 0};  // unfolded: flat and adjacent, fine
  EXPECT_EQ(ct::findSelfIntersections(fold).pairs.size(), 0u);
  // Sharing one vertex, the opposite edge of one piercing the other.
  TriangleMesh pierce;
  pierce.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}};
  pierce.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(ct::findSelfIntersections(pierce).pairs.size(), 1u);
  pierce.vertices[3] = {3, -3, -1};
  pierce.vertices[4] = {3, -3, 1};  // in the plane x = -y: meets the first face only at the shared vertex
  EXPECT_EQ(ct::findSelfIntersections(pierce).pairs.size(), 0u);
  // Degenerate faces are reported apart.
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  EXPECT_EQ(ct::findSelfIntersections(flat).degenerateFaces, std::vector<std::uint32_t>{0});
}

TEST(SelfIntersections, AgreesWithCgalOnADamagedIsosurface) {
  TriangleMesh m = isosurface(0.8);
  ASSERT_EQ(ct::findSelfIntersections(m).pairs.size(), 0u);
  // Push a few vertices through the opposite wall.
  for (std::size_t v = 0; v < m.vertices.size(); v += 997) m.vertices[v] = m.vertices[v] * -0.3;
  const ct::SelfIntersectionResult r = ct::findSelfIntersections(m);
  EXPECT_GT(r.pairs.size(), 10u);
  EXPECT_EQ(r.pairs.size(), countSelfIntersections(m));
}

TEST(SelfIntersections, AgreesWithCgalOnTheRealSkullIsosurface) {
  const std::string path = cttest::kSharedData + "/bone_cranium_ct_isosurface_400k.ply";
  if (!cttest::fs::exists(path)) GTEST_SKIP() << path << " not present";
  const TriangleMesh m = readMesh(path, {Units::Millimetres}).mesh;
  const ct::SelfIntersectionResult r = ct::findSelfIntersections(m);
  EXPECT_GT(r.pairs.size(), 0u);
  EXPECT_EQ(r.pairs.size() + r.degenerateFaces.size(), countSelfIntersections(m));
}

TEST(Decimation, KeepsTheSurfaceClosedOrientedAndFreeOfSelfIntersections) {
  const TriangleMesh fine = isosurface(0.6, 10);
  ASSERT_EQ(ct::findSelfIntersections(fine).pairs.size(), 0u);
  const double volume = signedVolume(fine);
  for (std::size_t target : {std::size_t(20000), std::size_t(3000), std::size_t(600)}) {
    ct::DecimationOptions o;
    o.targetFaces = target;
    ct::DecimationStats stats;
    const TriangleMesh d = ct::decimateQuadric(fine, o, &stats);
    ValidationOptions noSelfIntersections;
    noSelfIntersections.checkSelfIntersections = false;
    const ValidationReport rep = validateMesh(d, noSelfIntersections);
    EXPECT_TRUE(rep.closed && rep.consistentlyOriented && rep.outwardOriented) << target;
    EXPECT_EQ(rep.topology.connectedComponents, 1u);
    EXPECT_EQ(rep.topology.degenerateFaces, 0u);
    EXPECT_TRUE(stats.reachedTarget) << target;
    EXPECT_LE(d.triangles.size(), target);
    EXPECT_EQ(ct::findSelfIntersections(d).pairs.size(), 0u) << target;
    EXPECT_NEAR(*rep.volumeMm3 / volume, 1.0, target >= 3000 ? 0.01 : 0.05) << target;
    ASSERT_EQ(stats.sourceVertex.size(), d.vertices.size());
  }
}

TEST(Decimation, LockedVerticesStayWhereTheyAre) {
  const TriangleMesh fine = isosurface(0.8);
  std::vector<std::uint8_t> locked(fine.vertices.size(), 0);
  for (std::size_t v = 0; v < fine.vertices.size(); ++v) locked[v] = fine.vertices[v].z > 15;  // the top of the rod
  ct::DecimationOptions o;
  o.targetFaces = fine.triangles.size() / 5;
  o.lockedVertices = &locked;
  ct::DecimationStats stats;
  const TriangleMesh d = ct::decimateQuadric(fine, o, &stats);
  std::size_t keptLocked = 0;
  for (std::size_t v = 0; v < d.vertices.size(); ++v)
    if (locked[stats.sourceVertex[v]]) {
      ++keptLocked;
      EXPECT_EQ(d.vertices[v], fine.vertices[stats.sourceVertex[v]]);
    }
  EXPECT_EQ(keptLocked, std::size_t(std::count(locked.begin(), locked.end(), 1)));
}

}  // namespace
