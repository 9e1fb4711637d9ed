#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "RepairTestMeshes.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Repair.h"
#include "reamsim/mesh/VolumetricRemesh.h"

namespace reamsim {
namespace {

void expectCleanSolid(const RepairResult& r, double volume, double relTolerance) {
  EXPECT_TRUE(r.report.success()) << toText(r.report);
  const ValidationReport v = validateMesh(r.mesh);
  EXPECT_TRUE(v.isCleanSolid()) << toText(v);
  ASSERT_TRUE(v.volumeMm3.has_value());
  EXPECT_NEAR(*v.volumeMm3, volume, volume * relTolerance);
}

TEST(Repair, CleanMeshIsLeftAlone) {
  const TriangleMesh box = test::unitBox(10, 2);
  const RepairResult r = repairMesh(box);
  ASSERT_EQ(r.report.actions.size(), 1u);
  EXPECT_NE(r.report.actions[0].find("none needed"), std::string::npos);
  EXPECT_EQ(r.mesh.triangles, box.triangles);
  EXPECT_FALSE(r.report.remeshed);
}

TEST(Repair, MergesSoupVertices) {
  const RepairResult r = repairMesh(test::asSoup(test::unitBox(10, 2)));
  expectCleanSolid(r, 1000, 1e-12);
  EXPECT_GT(r.report.mergedVertices, 0u);
  EXPECT_FALSE(r.report.remeshed);
}

TEST(Repair, DropsDegenerateAndDuplicateFaces) {
  TriangleMesh m = test::unitBox(10, 2);
  m.triangles.push_back(m.triangles[3]);   // duplicate
  m.triangles.push_back({0, 0, 1});        // repeated index
  const RepairResult r = repairMesh(m);
  expectCleanSolid(r, 1000, 1e-12);
  EXPECT_EQ(r.report.removedFaces, 2u);
}

TEST(Repair, ClosesSmallHole) {
  TriangleMesh m = test::unitBox(10, 2);
  m.triangles.erase(m.triangles.begin());
  const RepairResult r = repairMesh(m);
  expectCleanSolid(r, 1000, 1e-12);
  EXPECT_EQ(r.report.holesClosed, 1u);
}

TEST(Repair, OrientsFlippedFacesAndInwardMeshes) {
  TriangleMesh m = test::unitBox(10, 2);
  std::swap(m.triangles[5][1], m.triangles[5][2]);
  expectCleanSolid(repairMesh(m), 1000, 1e-12);

  TriangleMesh inward = test::unitBox(10, 2);
  for (Triangle& t : inward.triangles) std::swap(t[1], t[2]);
  const RepairResult r = repairMesh(inward);
  expectCleanSolid(r, 1000, 1e-12);
  EXPECT_TRUE(r.report.flippedToOutward);
}

TEST(Repair, SelfIntersectingSoupIsRemeshedFaithfully) {
  const TriangleMesh a = test::unitBox(10, 1);
  const TriangleMesh overlapping = test::merged(a, test::translated(a, {5, 5, 5}));
  RepairOptions options;
  options.remesh.voxelMm = 0.25;
  const RepairResult r = repairMesh(overlapping, options);
  ASSERT_TRUE(r.report.remeshed);
  // The union of the two boxes: 2000 - 125 = 1875 mm³; the remesh bevels sharp edges within a voxel.
  expectCleanSolid(r, 1875, 0.02);
  ASSERT_TRUE(r.report.remesh.has_value());
  EXPECT_LT(r.report.remesh->maxOutputToInputMm, 0.25 * 1.8);
  EXPECT_GT(r.report.remesh->maxOutputToInputMm, 0.0);
  bool said = false;
  for (const std::string& a2 : r.report.actions) said |= a2.find("volumetric remesh") != std::string::npos;
  EXPECT_TRUE(said) << toText(r.report);
}

// A remesh beyond its limits is refused before the work, and the repair reports it (the mesh as the
// topological repair left it, not a clean solid) instead of throwing: an importer shows the mesh as read.
bool saysRemeshRefused(const RepairResult& r, const std::string& detail) {
  for (const std::string& a : r.report.actions)
    if (a.find("volumetric remesh refused") != std::string::npos && a.find(detail) != std::string::npos) return true;
  return false;
}

TEST(Repair, RemeshRefusesHugeGridsClearly) {
  RepairOptions options;
  options.remesh.voxelMm = 1e-4;
  const TriangleMesh a = test::unitBox(10, 1);
  const RepairResult r = repairMesh(test::merged(a, test::translated(a, {5, 5, 5})), options);
  EXPECT_FALSE(r.report.success());
  EXPECT_FALSE(r.report.remeshed);
  EXPECT_TRUE(saysRemeshRefused(r, "exceeds the limit")) << toText(r.report);
  EXPECT_TRUE(saysRemeshRefused(r, "the mesh spans 15 x 15 x 15 mm")) << toText(r.report);
  EXPECT_FALSE(r.mesh.empty());
}

// Found by fuzzing `reamsim-cli export --repair`: one vertex of a box moved 65.5 m away makes slivers whose
// grid (88 million points) is within the grid's limit but lies nearly all (82 million) in the band near the surface,
// which the remesh would have sampled point by point for hours. With the default options, as the CLI and the
// GUI's import call it.
TEST(Repair, RemeshRefusesAHugeBandBeforeTheWork) {
  TriangleMesh m = test::unitBox(10, 1);
  std::size_t far = 0;
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    if (m.vertices[i].x == 0 && m.vertices[i].y == 10 && m.vertices[i].z == 0) far = i;
  m.vertices[far].x = 65536;  // folds two faces through others: self-intersecting, so the repair remeshes
  const RepairResult r = repairMesh(m);
  EXPECT_FALSE(r.report.success());
  EXPECT_TRUE(saysRemeshRefused(r, "grid points near the surface exceeds the limit")) << toText(r.report);
  EXPECT_TRUE(saysRemeshRefused(r, "the mesh spans 65536 x 10 x 10 mm")) << toText(r.report);
}

TEST(Repair, VolumetricRemeshChecksItsLimits) {
  const TriangleMesh a = test::unitBox(10, 1);
  const TriangleMesh boxes = test::merged(a, test::translated(a, {5, 5, 5}));
  RemeshOptions options;
  options.voxelMm = 0.5;
  options.maxBandPoints = 1000;  // the two boxes' band at 0.5 mm holds several thousand
  try {
    volumetricRemesh(boxes, options);
    FAIL() << "expected the band limit to refuse";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the limit of 1000"), std::string::npos) << e.what();
  }
  options.maxBandPoints = 15'000'000;
  options.maxWindingTerms = 1e4;  // several thousand band points, several terms each
  try {
    volumetricRemesh(boxes, options);
    FAIL() << "expected the winding-term limit to refuse";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("winding-number terms"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("over 24 triangles"), std::string::npos) << e.what();
  }
  options.maxWindingTerms = RemeshOptions{}.maxWindingTerms;
  EXPECT_FALSE(volumetricRemesh(boxes, options).mesh.empty());
}

// The 400k CT skull (open, 386 self-intersecting pairs after merging): its remesh summed the winding number
// over every triangle at every band point (3.7e12 solid angles at 0.5 mm, hours; session 46 refused it at
// once). Over the tree of clusters (FastWindingNumber) it is repaired, with the import's options: the grid
// coarsened from 0.5 mm to about 1 mm (at 0.5 mm: 17 million triangles out after ~4 minutes; at ~1 mm about
// 4 million in about a minute, measured session 47).
TEST(Repair, LargeDirtyMeshIsRemeshed) {
  const std::string file = std::string(REAMSIM_SHARED_DATA_DIR) + "/bone_cranium_ct_isosurface_400k.ply";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not present";
  const RepairOptions options = importRepairOptions();
  const RepairResult r = repairMesh(readMesh(file).mesh, options);
  ASSERT_TRUE(r.report.remeshed) << toText(r.report);
  EXPECT_TRUE(r.report.success()) << toText(r.report);
  EXPECT_EQ(r.report.after.selfIntersectingPairs.value_or(1), 0u);
  // Coarsened, and said so.
  EXPECT_EQ(r.report.remesh->requestedVoxelMm, 0.5);
  EXPECT_GT(r.report.remesh->voxelMm, 0.8);
  EXPECT_LT(r.report.remesh->voxelMm, 1.2);
  EXPECT_GT(r.report.remesh->requestedBandPoints, options.remesh.coarsenAboveBandPoints);
  EXPECT_NE(toText(r.report).find("remesh grid coarsened from 0.5 to"), std::string::npos) << toText(r.report);
  EXPECT_LT(r.mesh.triangles.size(), 5'000'000u);
  // The rebuilt surface follows the input: on average within about half a voxel of it.
  EXPECT_LT(r.report.remesh->meanOutputToInputMm, 0.75);
  EXPECT_LT(r.report.remesh->meanInputToOutputMm, 0.2);
  // The tree's point of it: a band point costs a few hundred terms, not the direct sum's 400k solid angles.
  EXPECT_GT(r.report.remesh->windingTermsPerPoint, 0.0);
  EXPECT_LT(r.report.remesh->windingTermsPerPoint, 4000.0);
}

TEST(Repair, ImportOptionsKeepSmallMeshesAtTheRequestedGrid) {
  // The two boxes' band at 0.25 mm holds tens of thousands of points: under the import's budget, the grid
  // is the one asked for; over a small budget it is coarsened until the band fits.
  const TriangleMesh a = test::unitBox(10, 1);
  const TriangleMesh boxes = test::merged(a, test::translated(a, {5, 5, 5}));
  RepairOptions options = importRepairOptions();
  options.remesh.voxelMm = 0.25;
  const RepairResult kept = repairMesh(boxes, options);
  ASSERT_TRUE(kept.report.success()) << toText(kept.report);
  EXPECT_EQ(kept.report.remesh->voxelMm, 0.25);
  EXPECT_EQ(toText(kept.report).find("coarsened"), std::string::npos);
  options.remesh.coarsenAboveBandPoints = 5000;
  const RepairResult coarse = repairMesh(boxes, options);
  ASSERT_TRUE(coarse.report.success()) << toText(coarse.report);
  EXPECT_GT(coarse.report.remesh->voxelMm, 0.25);
  EXPECT_GT(coarse.report.remesh->requestedBandPoints, 5000u);
  EXPECT_NE(toText(coarse.report).find("remesh grid coarsened from 0.25 to"), std::string::npos) << toText(coarse.report);
  EXPECT_LT(coarse.mesh.triangles.size(), kept.mesh.triangles.size());
}

TEST(Repair, ReportsProgressAndStopsWhenCancelled) {
  const TriangleMesh a = test::unitBox(10, 1);
  const TriangleMesh boxes = test::merged(a, test::translated(a, {5, 5, 5}));  // needs the remesh
  RepairOptions options;
  std::vector<std::pair<double, std::string>> seen;
  options.progress = [&](double f, const std::string& stage) {
    seen.emplace_back(f, stage);
    return true;
  };
  const RepairResult r = repairMesh(boxes, options);
  ASSERT_TRUE(r.report.success()) << toText(r.report);
  ASSERT_GE(seen.size(), 6u);
  EXPECT_EQ(seen.front().first, 0.0);
  EXPECT_EQ(seen.back(), std::make_pair(1.0, std::string("done")));
  std::vector<std::string> stages;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (i > 0) {
      EXPECT_GE(seen[i].first, seen[i - 1].first) << seen[i].second;  // never goes back
    }
    if (stages.empty() || stages.back() != seen[i].second) stages.push_back(seen[i].second);
  }
  for (const char* expected : {"validation", "topological repair", "remesh: inside and outside near the surface",
                               "remesh: marching tetrahedra", "validation of the result"})
    EXPECT_NE(std::find(stages.begin(), stages.end(), expected), stages.end()) << expected;

  // Asked to stop when the remesh starts: it stops there, with the stage named.
  options.progress = [](double, const std::string& stage) { return stage.rfind("remesh", 0) != 0; };
  try {
    repairMesh(boxes, options);
    FAIL() << "expected the repair to stop";
  } catch (const RepairCancelled& e) {
    EXPECT_EQ(e.stage(), "remesh: winding-number tree");  // the remesh's first check
    EXPECT_NE(std::string(e.what()).find("cancelled"), std::string::npos);
  }
}

// The stages after the band (marching tetrahedra, decimation, the distances to the input: seconds each at
// millions of triangles) report inside their share of the progress and stop there when asked, not only
// at their start.
TEST(Repair, StopsInsideTheRemeshsLaterStagesWhenCancelled) {
  const TriangleMesh a = test::unitBox(10, 1);
  const TriangleMesh boxes = test::merged(a, test::translated(a, {5, 5, 5}));
  // `before`: where the stop must come before, as a fraction of the remesh (the repair maps it onto [0.15,
  // 0.9]): the end of marching tetrahedra, of the decimation's first attempt (its stop predicate, not the
  // next attempt's start), of the first distance (its slices, not the second distance's start).
  struct Stage {
    const char* name;
    std::size_t targetTriangles;
    double before;
  };
  for (const Stage& stage : {Stage{"remesh: marching tetrahedra", 0, 0.75}, Stage{"remesh: decimation", 4000, 0.8},
                             Stage{"remesh: distance to the input", 0, 0.92}}) {
    SCOPED_TRACE(stage.name);
    RepairOptions options;
    options.remesh.voxelMm = 0.25;  // ~38,000 triangles, ~19,000 vertices
    options.remesh.targetTriangles = stage.targetTriangles;
    double first = -1, stoppedAt = -1;  // the stage's first report, and a later one past it
    options.progress = [&](double f, const std::string& name) {
      if (name != stage.name) return true;
      if (first < 0) first = f;
      if (f <= first) return true;
      stoppedAt = f;
      return false;
    };
    try {
      repairMesh(boxes, options);
      ADD_FAILURE() << "expected the repair to stop";
    } catch (const RepairCancelled& e) {
      EXPECT_EQ(e.stage(), stage.name);
    }
    EXPECT_GT(stoppedAt, first);
    EXPECT_LT(stoppedAt, 0.15 + 0.75 * stage.before);
  }
}

TEST(Repair, RemeshWithDecimationStaysClean) {
  const TriangleMesh a = test::unitBox(10, 1);
  RepairOptions options;
  options.remesh.voxelMm = 0.5;
  options.remesh.targetTriangles = 2000;
  const RepairResult r = repairMesh(test::merged(a, test::translated(a, {5, 5, 5})), options);
  expectCleanSolid(r, 1875, 0.03);
  EXPECT_LE(r.mesh.triangles.size(), 2000u * 3 * 3 / 4);
}

}  // namespace
}  // namespace reamsim
