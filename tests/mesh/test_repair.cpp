#include <gtest/gtest.h>

#include "RepairTestMeshes.h"
#include "reamsim/mesh/Repair.h"

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

TEST(Repair, RemeshRefusesHugeGridsClearly) {
  RepairOptions options;
  options.remesh.voxelMm = 1e-4;
  const TriangleMesh a = test::unitBox(10, 1);
  try {
    repairMesh(test::merged(a, test::translated(a, {5, 5, 5})), options);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the limit"), std::string::npos) << e.what();
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
