// Real third-party meshes from ../shared/data (skipped when that folder is absent).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "reamsim/mesh/MeshIO.h"

using namespace reamsim;

namespace {

std::string shared(const std::string& name) { return std::string(REAMSIM_SHARED_DATA_DIR) + "/" + name; }

TEST(io_RealFiles, ScapulaVtpInMetresIsScaledToMillimetres) {
  const std::string file = shared("scapula_R_opensim.vtp");
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not present";
  const LoadedMesh m = readMesh(file);
  EXPECT_EQ(m.format, "vtp");
  EXPECT_EQ(m.mesh.vertexCount(), 770u);
  // NumberOfPolys="1541": 1539 triangles and 2 quads, which fan-triangulate to 1543 triangles.
  EXPECT_EQ(m.mesh.triangleCount(), 1543u);
  EXPECT_EQ(m.scaleToMillimetres, 1000.0);
  bool unitsNote = false, quadNote = false;
  for (const std::string& n : m.notes) {
    unitsNote |= n.find("coordinates look like metres") != std::string::npos;
    quadNote |= n == "2 polygons with >3 vertices were triangulated";
  }
  EXPECT_TRUE(unitsNote);
  EXPECT_TRUE(quadNote);
  const double diagonal = computeBounds(m.mesh).diagonal();
  EXPECT_GT(diagonal, 100.0);
  EXPECT_LT(diagonal, 300.0);
  RecordProperty("scapula_triangles", static_cast<int>(m.mesh.triangleCount()));
  RecordProperty("scapula_diagonal_mm", std::to_string(diagonal));
}

TEST(io_RealFiles, CraniumPlyInMillimetresIsNotScaled) {
  const std::string file = shared("bone_cranium_ct_isosurface_400k.ply");
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not present";
  const LoadedMesh m = readMesh(file);
  EXPECT_EQ(m.format, "ply-binary");
  EXPECT_EQ(m.mesh.vertexCount(), 205777u);
  EXPECT_EQ(m.mesh.triangleCount(), 399757u);
  EXPECT_EQ(m.scaleToMillimetres, 1.0);
  EXPECT_TRUE(m.notes.empty());
  const Bounds b = computeBounds(m.mesh);
  EXPECT_NEAR(b.min.x, 12, 2);
  EXPECT_NEAR(b.max.x, 237, 2);
  EXPECT_NEAR(b.max.y, 0, 2);
  EXPECT_NEAR(b.max.z, 158, 2);
}

}  // namespace
