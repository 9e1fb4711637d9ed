// The bundled scapula (resources/, CC BY 3.0) before and after repair, and the committed repaired mesh
// against a fresh repair with the same settings.
#include <gtest/gtest.h>

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Repair.h"

namespace reamsim {
namespace {

const std::string kOriginal = std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_opensim.vtp";
const std::string kRepaired = std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_repaired.ply";

TEST(ScapulaRepair, OriginalIsDirtyAsDocumented) {
  const LoadedMesh m = readMesh(kOriginal);
  EXPECT_DOUBLE_EQ(m.scaleToMillimetres, 1000.0);
  const ValidationReport r = validateMesh(m.mesh);
  EXPECT_EQ(r.vertices, 770u);
  EXPECT_EQ(r.triangles, 1543u);
  EXPECT_FALSE(r.closed);
  EXPECT_GT(r.topology.boundaryEdges + r.topology.nonManifoldEdges, 0u);
  EXPECT_GT(r.selfIntersectingPairs.value(), 200u);
}

TEST(ScapulaRepair, RepairMatchesCommittedResourceAndIsFaithful) {
  const LoadedMesh original = readMesh(kOriginal);
  RepairOptions options;  // the settings used for the resource (docs/DEFAULT_CASE.md)
  options.remesh.voxelMm = 0.75;
  options.remesh.targetTriangles = 10000;
  const RepairResult r = repairMesh(original.mesh, options);
  ASSERT_TRUE(r.report.success()) << toText(r.report);
  ASSERT_TRUE(r.report.remeshed);
  EXPECT_EQ(r.report.after.selfIntersectingPairs.value(), 0u);
  EXPECT_EQ(r.report.after.topology.connectedComponents, 1u);
  // Faithful: within 2 mm everywhere (0.75 mm grid) and ~0.1 mm on average, both ways.
  EXPECT_LT(r.report.remesh->maxOutputToInputMm, 2.0);
  EXPECT_LT(r.report.remesh->maxInputToOutputMm, 1.0);
  EXPECT_LT(r.report.remesh->meanOutputToInputMm, 0.1);
  EXPECT_LT(r.report.remesh->meanInputToOutputMm, 0.15);
  // SOURCES.md: volume ≈ 62.8 cm³.
  EXPECT_NEAR(*r.report.after.volumeMm3, 62800, 62800 * 0.02);

  ReadOptions mm;
  mm.units = Units::Millimetres;
  const TriangleMesh committed = readMesh(kRepaired, mm).mesh;
  EXPECT_EQ(committed.triangles.size(), r.mesh.triangles.size());
  EXPECT_NEAR(signedVolume(committed), signedVolume(r.mesh), 1e-6 * signedVolume(r.mesh));
  const ValidationReport c = validateMesh(committed);
  EXPECT_TRUE(c.isCleanSolid()) << toText(c);
}

}  // namespace
}  // namespace reamsim
