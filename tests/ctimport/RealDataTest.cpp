// Acceptance on the real CT volumes of ../shared/data (skipped when absent): the headsq NRRD (detached
// header, 93 slice files, not in HU) and the clinical cranium CT (MetaImage, HU) give closed meshes free of
// self-intersections — checked again, independently, with the Foundation's CGAL count. Face counts,
// volumes and times are printed for the report; speed itself is measured by the benchmark
// (reamsim-cli import-ct --json, docs/CT_IMPORT.md), not here.
#include <gtest/gtest.h>

#include <cstdio>

#include "TestUtil.h"
#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "reamsim/mesh/Validation.h"

namespace {

using namespace reamsim;

void expectCleanBone(const ct::ImportResult& r, const char* name) {
  const ValidationReport& v = r.report.validation;
  EXPECT_TRUE(v.isCleanSolid()) << ct::toText(r.report);
  EXPECT_EQ(v.topology.connectedComponents, 1u);
  EXPECT_FALSE(r.report.repaired);
  EXPECT_EQ(countSelfIntersections(r.mesh), 0u) << "CGAL disagrees with the import's own check";
  std::printf("[ %s ] %zu faces, %.0f mm3, isosurface %zu faces, pipeline %.0f ms\n", name, v.triangles,
              v.volumeMm3.value_or(0), r.report.isosurfaceFaces, r.report.totalMs);
}

TEST(RealData, HeadsqNrrdWithDetachedHeaderAndSliceFiles) {
  const std::string path = cttest::kSharedData + "/ct_headsq/quarter.nhdr";
  if (!cttest::fs::exists(path)) GTEST_SKIP() << path << " not present";
  const ct::CtVolume v = ct::readVolume(path);
  EXPECT_EQ(v.dims, (std::array<int, 3>{64, 64, 93}));
  EXPECT_EQ(v.spacing, (std::array<double, 3>{3.2, 3.2, 1.5}));
  EXPECT_EQ(v.space, ct::PatientSpace::Unspecified);  // "3D-left-handed": no anatomical frame
  ct::ImportOptions o;
  o.lowerThreshold = 1150;  // not HU: the classic bone iso-value of this data set
  const ct::ImportResult r = ct::importBone(v, o);
  expectCleanBone(r, "headsq");
  EXPECT_EQ(r.space, ct::PatientSpace::Unspecified);
  EXPECT_EQ(r.report.fieldOfViewCuts, (std::vector<std::string>{"-k", "+k"}));  // the skull leaves the scan
  // The note that warns about non-HU data is there.
  bool warned = false;
  for (const std::string& n : r.report.notes) warned = warned || n.find("not Hounsfield") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(RealData, ClinicalCraniumCtInHounsfieldUnits) {
  const std::string path = cttest::kSharedData + "/ct_cranium_invesalius_256x256x108.mha";
  if (!cttest::fs::exists(path)) GTEST_SKIP() << path << " not present";
  const ct::CtVolume v = ct::readVolume(path);
  EXPECT_EQ(v.dims, (std::array<int, 3>{256, 256, 108}));
  EXPECT_NEAR(v.spacing[0], 0.9570312, 1e-6);
  EXPECT_EQ(v.space, ct::PatientSpace::LPS);
  const ct::ImportResult r = ct::importBone(v);  // defaults: 250 HU, 150k faces
  expectCleanBone(r, "cranium");
  EXPECT_TRUE(r.report.decimated);
  EXPECT_LE(r.report.validation.triangles, 150000u);
  EXPECT_GT(r.report.validation.triangles, 140000u);
  // Decimation and smoothing keep the isosurface's volume.
  EXPECT_NEAR(*r.report.validation.volumeMm3 / r.report.isosurfaceVolumeMm3, 1.0, 0.002);
}

}  // namespace
