#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "RepairTestMeshes.h"
#include "reamsim/mesh/Validation.h"

namespace reamsim {
namespace {

TEST(Validation, CleanBoxIsASolid) {
  const ValidationReport r = validateMesh(test::unitBox(10, 3));
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.consistentlyOriented);
  EXPECT_TRUE(r.outwardOriented);
  EXPECT_EQ(r.selfIntersectingPairs.value(), 0u);
  EXPECT_EQ(r.topology.degenerateFaces, 0u);
  EXPECT_EQ(r.topology.connectedComponents, 1u);
  ASSERT_TRUE(r.volumeMm3.has_value());
  EXPECT_NEAR(*r.volumeMm3, 1000.0, 1e-9);
  EXPECT_NEAR(r.areaMm2, 600.0, 1e-9);
  EXPECT_TRUE(r.isCleanSolid());
}

TEST(Validation, CoincidentVerticesAreToldApartFromRealBordersAndIntersections) {
  const TriangleMesh box = test::unitBox(10, 2);
  EXPECT_EQ(countCoincidentVertices(box), 0u);
  EXPECT_FALSE(validateMesh(box).afterMergingCoincident.has_value());

  // The same box written as a triangle soup: every triangle its own three vertices.
  TriangleMesh soup;
  for (const Triangle& t : box.triangles) {
    const std::uint32_t base = static_cast<std::uint32_t>(soup.vertices.size());
    for (std::uint32_t v : t) soup.vertices.push_back(box.vertices[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  const ValidationReport r = validateMesh(soup);
  EXPECT_EQ(r.coincidentVertices, soup.vertices.size() - box.vertices.size());
  EXPECT_EQ(r.topology.boundaryEdges, 3 * soup.triangles.size());
  EXPECT_GT(r.selfIntersectingPairs.value(), 0u);  // neighbours touch at points they do not share by index
  ASSERT_TRUE(r.afterMergingCoincident.has_value());
  EXPECT_EQ(r.afterMergingCoincident->boundaryEdges, 0u);
  EXPECT_EQ(r.afterMergingCoincident->nonManifoldEdges, 0u);
  EXPECT_EQ(r.afterMergingCoincident->selfIntersectingPairs.value(), 0u);
  EXPECT_NE(toText(r).find("coincident vertices:    " + std::to_string(r.coincidentVertices)), std::string::npos);
  EXPECT_NE(toJson(r).find("after_merging_coincident"), std::string::npos);

  std::size_t merged = 0;
  const TriangleMesh welded = mergeCoincidentVertices(soup, &merged);
  EXPECT_EQ(merged, r.coincidentVertices);
  EXPECT_EQ(welded.vertices.size(), box.vertices.size());
  EXPECT_TRUE(validateMesh(welded).isCleanSolid());
}

TEST(Validation, OpenMeshHasBoundaryAndNoVolume) {
  TriangleMesh m = test::unitBox(10, 2);
  m.triangles.pop_back();
  const ValidationReport r = validateMesh(m);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.topology.boundaryEdges, 3u);
  EXPECT_FALSE(r.volumeMm3.has_value());
  EXPECT_FALSE(r.isCleanSolid());
}

TEST(Validation, FlippedFaceIsInconsistent) {
  TriangleMesh m = test::unitBox(10, 2);
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  const ValidationReport r = validateMesh(m);
  EXPECT_TRUE(r.closed);
  EXPECT_FALSE(r.consistentlyOriented);
  EXPECT_EQ(r.topology.inconsistentEdges, 3u);
}

TEST(Validation, InwardBoxIsNotOutward) {
  TriangleMesh m = test::unitBox(10, 1);
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  const ValidationReport r = validateMesh(m);
  EXPECT_TRUE(r.consistentlyOriented);
  EXPECT_FALSE(r.outwardOriented);
}

TEST(Validation, OverlappingBoxesSelfIntersect) {
  const TriangleMesh a = test::unitBox(10, 1);
  const TriangleMesh m = test::merged(a, test::translated(a, {5, 5, 5}));
  const ValidationReport r = validateMesh(m);
  EXPECT_TRUE(r.closed);
  EXPECT_GT(r.selfIntersectingPairs.value(), 0u);
  EXPECT_EQ(r.topology.connectedComponents, 2u);
}

TEST(Validation, NonManifoldEdgeAndDegenerateFace) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {2, 0, 0}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {0, 1, 5}};  // edge 0-1 used 3 times; face 4 collinear
  const ValidationReport r = validateMesh(m);
  EXPECT_EQ(r.topology.nonManifoldEdges, 1u);
  EXPECT_EQ(r.topology.degenerateFaces, 1u);
  EXPECT_FALSE(r.closed);
}

TEST(Validation, JsonAndTextNameEveryField) {
  const ValidationReport r = validateMesh(test::unitBox());
  const std::string json = toJson(r);
  for (const char* key : {"vertices", "triangles", "closed", "boundary_edges", "non_manifold_edges",
                          "consistently_oriented", "self_intersecting_pairs", "degenerate_faces", "volume_mm3",
                          "bounds_mm"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  EXPECT_NE(toText(r).find("self-intersecting pairs: 0"), std::string::npos);
}

// The count runs slab by slab along the longest axis (so that a cancel is seen between slabs): a pair is
// counted in one slab only, whichever the slabs. Two overlapping boxes cross along lines through many slabs.
TEST(Validation, SelfIntersectionCountDoesNotDependOnTheSlabs) {
  const TriangleMesh a = test::unitBox(10, 20);
  const TriangleMesh boxes = test::merged(a, test::translated(a, {5, 3.3, 2.7}));
  // And a degenerate triangle (three distinct, collinear corners) across the boxes: CGAL reports it as a pair
  // with itself in every slab it reaches; it counts once.
  TriangleMesh withNeedle = boxes;
  const auto v = std::uint32_t(withNeedle.vertices.size());
  withNeedle.vertices.insert(withNeedle.vertices.end(), {{-1, 4.1, 4.2}, {7, 4.1, 4.2}, {16, 4.1, 4.2}});
  withNeedle.triangles.push_back({v, v + 1, v + 2});
  for (const TriangleMesh* mesh : {&boxes, static_cast<const TriangleMesh*>(&withNeedle)}) {
    const std::size_t n = mesh->triangles.size();
    // One slab: CGAL's self_intersections over every face, as before slabs.
    const std::size_t whole = detail::countSelfIntersectionsInSlabs(*mesh, 1000000, {}, n);
    EXPECT_GT(whole, 100u);
    for (std::size_t perSlab : {n / 3, std::size_t(500), std::size_t(97)}) {
      SCOPED_TRACE(perSlab);
      EXPECT_EQ(detail::countSelfIntersectionsInSlabs(*mesh, 1000000, {}, perSlab), whole);
      EXPECT_EQ(detail::countSelfIntersectionsInSlabs(*mesh, 7, {}, perSlab), 7u);  // the limit still holds
    }
  }
  EXPECT_EQ(detail::countSelfIntersectionsInSlabs(withNeedle, 1000000, {}, 97),
            detail::countSelfIntersectionsInSlabs(boxes, 1000000, {}, 97) + 1);

  // Two long bars whose faces run the whole length: every face would be in every slab, so the count falls
  // back to one slab, with the same result.
  const TriangleMesh bar = buildBox(Bounds{{0, 0, 0}, {100, 1, 1}}, 1);
  const TriangleMesh bars = test::merged(bar, test::translated(bar, {50, 0.5, 0.5}));
  const std::size_t barsWhole = detail::countSelfIntersectionsInSlabs(bars, 1000000, {}, bars.triangles.size());
  EXPECT_GT(barsWhole, 0u);
  EXPECT_EQ(detail::countSelfIntersectionsInSlabs(bars, 1000000, {}, 3), barsWhole);
}

TEST(Validation, SelfIntersectionCountStopsWhenCancelled) {
  const TriangleMesh a = test::unitBox(10, 20);
  const TriangleMesh boxes = test::merged(a, test::translated(a, {5, 3.3, 2.7}));
  std::vector<double> seen;
  const RepairProgress progress = [&](double f, const std::string&) {
    seen.push_back(f);
    return seen.size() < 4;  // the start, the mesh built, a first slab: then stop
  };
  ValidationOptions options;
  options.progress = StageProgress{&progress, 0.2, 0.4, "validation"};
  try {
    detail::countSelfIntersectionsInSlabs(boxes, 1000000, options.progress, 500);
    ADD_FAILURE() << "expected the count to stop";
  } catch (const RepairCancelled& e) {
    EXPECT_EQ(e.stage(), "validation");
  }
  ASSERT_EQ(seen.size(), 4u);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_GE(seen[i], 0.2);
    EXPECT_LT(seen[i], 0.4);
    if (i > 0) {
      EXPECT_GE(seen[i], seen[i - 1]);  // never goes back
    }
  }
  EXPECT_GT(seen.back(), seen.front());
  const RepairProgress stopAtOnce = [](double, const std::string&) { return false; };
  options.progress.progress = &stopAtOnce;
  EXPECT_THROW(validateMesh(boxes, options), RepairCancelled);  // validateMesh passes it on
}

}  // namespace
}  // namespace reamsim
