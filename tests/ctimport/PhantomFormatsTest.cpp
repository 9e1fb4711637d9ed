// Acceptance: a phantom of known geometry (sphere pierced by a cylinder of bone density in soft tissue,
// plus a loose fragment), written by the test in every supported format with an oblique orientation, comes
// back as one closed, clean mesh in the right place with the volume within 1 % of the analytic value.
#include <gtest/gtest.h>

#include <clocale>
#include <cstdio>
#include <optional>

#include <algorithm>
#include <cmath>
#include <functional>

#include "Phantom.h"
#include "TestUtil.h"
#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/VolumeIO.h"

namespace {

using namespace reamsim;
using phantom::Grid;

struct Format {
  std::string name;
  std::function<std::string(const cttest::fs::path& dir, const Grid&, const std::vector<float>&)> write;
  ct::PatientSpace fileSpace;  // the space the reader must report
};

std::vector<Format> formats() {
  using P = ct::PatientSpace;
  return {
      {"nrrd_attached", [](auto d, auto& g, auto& v) { auto p = (d / "v.nrrd").string(); phantom::writeNrrd(p, g, v); return p; }, P::LPS},
      {"nrrd_detached_gzip_ras", [](auto d, auto& g, auto& v) { auto p = (d / "v.nhdr").string(); phantom::writeNrrdDetachedGzipRas(p, g, v); return p; }, P::RAS},
      {"nrrd_slice_files", [](auto d, auto& g, auto& v) { auto p = (d / "v.nhdr").string(); phantom::writeNrrdSlices(p, g, v); return p; }, P::LPS},
      {"mha", [](auto d, auto& g, auto& v) { auto p = (d / "v.mha").string(); phantom::writeMha(p, g, v, false); return p; }, P::LPS},
      {"mha_zlib", [](auto d, auto& g, auto& v) { auto p = (d / "v.mha").string(); phantom::writeMha(p, g, v, true); return p; }, P::LPS},
      {"mhd_raw", [](auto d, auto& g, auto& v) { auto p = (d / "v.mhd").string(); phantom::writeMhdRaw(p, g, v); return p; }, P::LPS},
      {"nifti", [](auto d, auto& g, auto& v) { auto p = (d / "v.nii").string(); phantom::writeNifti(p, g, v); return p; }, P::RAS},
      {"nifti_gz", [](auto d, auto& g, auto& v) { auto p = (d / "v.nii.gz").string(); phantom::writeNifti(p, g, v); return p; }, P::RAS},
      {"dicom_series", [](auto d, auto& g, auto& v) { auto p = (d / "series").string(); phantom::writeDicomSeries(p, g, v); return p; }, P::LPS},
      // RLE lossless, opened through one file of the series. (vtk-dicom cannot write the JPEG family,
      // which it reads through GDCM; no JPEG encoder is available to the tests.)
      // A CD's layout: the files two folders down under names of up to 8 characters (deeper than a scan of
      // the folder reaches), the folder above read through its DICOMDIR.
      {"dicom_dicomdir", [](auto d, auto& g, auto& v) {
         const auto root = d / "cd";
         phantom::writeDicomSeries((root / "DATA" / "S1").string(), g, v, "", "%s/IM%04d");
         std::vector<std::string> files;
         for (int k = 1; k <= g.dims[2]; ++k) {
           char name[32];
           std::snprintf(name, sizeof name, "DATA/S1/IM%04d", k);
           files.push_back(name);
         }
         phantom::writeDicomDir(root.string(), files);
         return root.string(); }, P::LPS},
      {"dicom_rle", [](auto d, auto& g, auto& v) { auto p = (d / "series").string(); phantom::writeDicomSeries(p, g, v, "1.2.840.10008.1.2.5"); return p + "/IM-0001.dcm"; }, P::LPS},
  };
}

// In the right place, the right way round: the cylinder's ends along its axis, within 0.6 mm.
void expectCylinderEndsInPlace(const TriangleMesh& mesh, const phantom::SphereAndCylinder& shape) {
  double top = -HUGE_VAL, bottom = HUGE_VAL;
  for (const Vec3& p : mesh.vertices) {
    top = std::max(top, dot(p - shape.center, shape.axis));
    bottom = std::min(bottom, dot(p - shape.center, shape.axis));
  }
  EXPECT_NEAR(top, shape.cylinderLength / 2, 0.6);
  EXPECT_NEAR(bottom, -shape.cylinderLength / 2, 0.6);
}

class PhantomFormats : public ::testing::TestWithParam<Format> {
 protected:
  static void SetUpTestSuite() {
    shape_.fragment = true;
    // Oblique axes and anisotropic voxels: orientation and spacing must be honoured, not assumed.
    grid_ = phantom::gridAround(shape_.center, 26, {0.9, 0.8, 1.0}, phantom::rotation({1, 2, 3}, 30));
    values_ = phantom::sample(grid_, [](const Vec3& p) { return shape_.inside(p); });
  }
  static phantom::SphereAndCylinder shape_;
  static Grid grid_;
  static std::vector<float> values_;
};
phantom::SphereAndCylinder PhantomFormats::shape_;
Grid PhantomFormats::grid_;
std::vector<float> PhantomFormats::values_;

TEST_P(PhantomFormats, ReadsGeometryAndImportsAClosedMeshOfTheRightVolume) {
  const Format& f = GetParam();
  const std::string path = f.write(cttest::scratch("formats_" + f.name), grid_, values_);
  const ct::CtVolume v = ct::readVolume(path);

  // Geometry as written (RAS files: x and y negated).
  EXPECT_EQ(v.space, f.fileSpace);
  EXPECT_EQ(v.dims, grid_.dims);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(v.spacing[std::size_t(a)], grid_.spacing[std::size_t(a)], 1e-5) << a;
  const auto toFile = [&](const Vec3& p) { return ct::convertPoint(p, ct::PatientSpace::LPS, f.fileSpace); };
  for (const auto& [i, j, k] : {std::array<int, 3>{0, 0, 0}, {grid_.dims[0] - 1, 3, 7}, {5, grid_.dims[1] - 1, grid_.dims[2] - 1}}) {
    const Vec3 expected = toFile(grid_.world(i, j, k)), got = v.indexToWorld(i, j, k);
    EXPECT_NEAR(norm(expected - got), 0.0, 1e-3) << i << "," << j << "," << k;
  }
  if (f.name == "dicom_rle") {  // really compressed: the reader names the transfer syntax it decoded
    bool rle = false;
    for (const std::string& n : v.notes) rle = rle || n.find("1.2.840.10008.1.2.5") != std::string::npos;
    EXPECT_TRUE(rle);
  }
  // Values: int16 round trip (the NIfTI one through scl_inter, DICOM through its rescale).
  const std::size_t probe = v.index(grid_.dims[0] / 2, grid_.dims[1] / 2, grid_.dims[2] / 2);
  EXPECT_NEAR(v.values[probe], std::round(values_[probe]), 0.51);

  ct::ImportOptions o;
  o.lowerThreshold = 620;  // half way between tissue (40) and bone (1200): the 50 % partial-volume surface
  o.targetFaces = 12000;
  const ct::ImportResult r = ct::importBone(v, o);
  const ValidationReport& rep = r.report.validation;
  EXPECT_EQ(r.space, ct::PatientSpace::LPS);
  EXPECT_TRUE(rep.isCleanSolid()) << ct::toText(r.report);
  EXPECT_EQ(rep.topology.connectedComponents, 1u);
  EXPECT_EQ(r.report.regions, 2u);  // main body and fragment; the fragment is dropped
  EXPECT_LE(rep.triangles, 12000u);
  ASSERT_TRUE(rep.volumeMm3);
  EXPECT_NEAR(*rep.volumeMm3 / shape_.mainVolume(), 1.0, 0.01) << "volume " << *rep.volumeMm3;
  // In the right place, the right way round: centroid at the centre, cylinder ends along the axis.
  EXPECT_NEAR(norm(cttest::solidCentroid(r.mesh) - shape_.center), 0.0, 0.3);
  expectCylinderEndsInPlace(r.mesh, shape_);
}

// The GUI's C library runs in the user's locale (QApplication sets it): a decimal-comma locale must not
// change the geometry read from a file (a DICOM spacing of "0.9" read as 0, say).
TEST_P(PhantomFormats, ReadsTheSameGeometryInADecimalCommaLocale) {
  const Format& f = GetParam();
  const std::string path = f.write(cttest::scratch("locale_" + f.name), grid_, values_);
  const std::string previous = std::setlocale(LC_ALL, nullptr);
  if (!std::setlocale(LC_ALL, "de_DE.UTF-8") && !std::setlocale(LC_ALL, "de_DE.utf8"))
    GTEST_SKIP() << "no de_DE.UTF-8 locale here (scripts/install-deps.sh generates it)";
  std::optional<ct::CtVolume> v;
  std::string error;
  try {
    v = ct::readVolume(path);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::setlocale(LC_ALL, previous.c_str());
  ASSERT_TRUE(v) << error;
  EXPECT_EQ(v->dims, grid_.dims);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(v->spacing[std::size_t(a)], grid_.spacing[std::size_t(a)], 1e-5) << a;
  const Vec3 expected = ct::convertPoint(grid_.world(3, 4, 5), ct::PatientSpace::LPS, f.fileSpace);
  EXPECT_NEAR(norm(expected - v->indexToWorld(3, 4, 5)), 0.0, 1e-3);
}

TEST_P(PhantomFormats, ReadingReportsProgressAndCanBeCancelled) {
  const Format& f = GetParam();
  const std::string path = f.write(cttest::scratch("progress_" + f.name), grid_, values_);
  std::vector<double> seen;
  ct::readVolume(path, [&](double fraction, const std::string& stage) {
    EXPECT_EQ(stage, "reading");
    seen.push_back(fraction);
    return true;
  });
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
  EXPECT_THROW(ct::readVolume(path, [](double, const std::string&) { return false; }), ct::ImportCancelled);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, PhantomFormats, ::testing::ValuesIn(formats()),
                         [](const ::testing::TestParamInfo<Format>& i) { return i.param.name; });

// A left-handed index frame (one axis reversed) must still give an outward, correctly placed solid.
TEST(PhantomOrientation, MirroredAxesGiveAnOutwardMeshInPlace) {
  phantom::SphereAndCylinder shape;
  shape.axis = normalized(Vec3{1, 1, 0});
  std::array<double, 9> d = phantom::rotation({0, 0, 1}, 15);
  for (int r = 0; r < 3; ++r) d[std::size_t(3 * r + 1)] = -d[std::size_t(3 * r + 1)];  // reverse axis j
  const Grid g = phantom::gridAround(shape.center, 26, {1.0, 1.0, 1.0}, d);
  const std::vector<float> hu = phantom::sample(g, [&](const Vec3& p) { return shape.inside(p); });
  const std::string path = (cttest::scratch("mirrored") / "m.nrrd").string();
  phantom::writeNrrd(path, g, hu);
  ct::ImportOptions o;
  o.lowerThreshold = 620;
  const ct::ImportResult r = ct::importBone(ct::readVolume(path), o);
  EXPECT_TRUE(r.report.validation.isCleanSolid()) << ct::toText(r.report);
  EXPECT_NEAR(*r.report.validation.volumeMm3 / shape.mainVolume(), 1.0, 0.01);
  EXPECT_NEAR(norm(cttest::solidCentroid(r.mesh) - shape.center), 0.0, 0.3);
}

}  // namespace

namespace {

// A volume resampled from sheared slices: a rectangular grid, and the phantom's import where it is (volume,
// centroid) and not sheared (the cylinder's ends where they are: a shear keeps volume and centroid, not these).
void expectRectifiedPhantomInPlace(const ct::CtVolume& v, const phantom::SphereAndCylinder& shape) {
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) EXPECT_NEAR(dot(v.axis(a), v.axis(b)), 0.0, 1e-9);
  ct::ImportOptions o;
  o.lowerThreshold = 620;
  const ct::ImportResult r = ct::importBone(v, o);
  EXPECT_TRUE(r.report.validation.isCleanSolid()) << ct::toText(r.report);
  EXPECT_NEAR(*r.report.validation.volumeMm3 / shape.mainVolume(), 1.0, 0.01);
  EXPECT_NEAR(norm(cttest::solidCentroid(r.mesh) - shape.center), 0.0, 0.3);
  expectCylinderEndsInPlace(r.mesh, shape);
}

// A gantry-tilted CT: the slices are parallel to each other but each is shifted within its plane (the gantry
// leaned 15° about the patient's left-right axis), so the slice-to-slice step is not along the slices'
// normal. The series is resampled onto a rectangular grid (with a note saying so) and comes back in place.
TEST(PhantomOrientation, GantryTiltedDicomSeriesIsResampledInPlace) {
  phantom::SphereAndCylinder shape;
  shape.axis = normalized(Vec3{0, 1, 2});
  const double tilt = 15 * M_PI / 180;
  std::array<double, 9> d{1, 0, 0, 0, 1, std::sin(tilt), 0, 0, std::cos(tilt)};  // columns: x, y, the step
  Grid g = phantom::gridAround(shape.center, 26, {0.9, 0.9, 1.25}, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  g.direction = d;
  g.origin = g.origin - Vec3{0, std::sin(tilt), 0} * (0.5 * g.spacing[2] * (g.dims[2] - 1));  // still around it
  const std::vector<float> hu = phantom::sample(g, [&](const Vec3& p) { return shape.inside(p); });
  const std::string dir = (cttest::scratch("gantry_tilt") / "series").string();
  phantom::writeDicomSeries(dir, g, hu);
  const ct::CtVolume v = ct::readVolume(dir);
  bool noted = false;
  for (const std::string& n : v.notes) noted = noted || n.find("gantry tilt of 15.0") != std::string::npos;
  EXPECT_TRUE(noted) << (v.notes.empty() ? "" : v.notes.front());
  expectRectifiedPhantomInPlace(v, shape);
}

// The same slant in an NRRD, MetaImage or NIfTI header (a gantry-tilted CT converted without correction: the
// slice step vector is not along the slices' normal): resampled as the DICOM reader does, with a note. The k
// axis leaning toward j or i, either way; i leaning toward j (a shear that reads as j leaning too); i leaning
// toward both j and k (only i can be the slanted axis).
TEST(PhantomOrientation, SlantedSlicesOfNrrdMetaImageAndNiftiAreResampledInPlace) {
  phantom::SphereAndCylinder shape;
  shape.axis = normalized(Vec3{0, 1, 2});
  const auto tanDeg = [](double d) { return std::tan(d * M_PI / 180); };
  struct Case {
    const char* file;
    std::function<void(const std::string&, const Grid&, const std::vector<float>&)> write;
    int slanted;  // the axis whose step leans
    Vec3 lean;    // added to that axis's unit vector (perpendicular to it)
    bool onlyReading = false;  // it leans toward both other axes: no other axis can be read as the slanted one
  };
  const std::vector<Case> cases = {
      {"tilted.nrrd", phantom::writeNrrd, 2, {0, tanDeg(15), 0}},
      {"tilted.mha", [](const std::string& f, const Grid& g, const std::vector<float>& hu) { phantom::writeMha(f, g, hu, true); }, 2, {tanDeg(15), 0, 0}},
      {"tilted.nii", phantom::writeNifti, 2, {0, -tanDeg(20), 0}},
      {"tilted_i.nrrd", phantom::writeNrrd, 0, {0, tanDeg(12), 0}},
      {"tilted_i_both.nrrd", phantom::writeNrrd, 0, {0, tanDeg(10), -tanDeg(10)}, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    Grid g = phantom::gridAround(shape.center, 26, {0.9, 0.9, 1.25}, {1, 0, 0, 0, 1, 0, 0, 0, 1});
    const std::size_t s = std::size_t(c.slanted);
    Vec3 unit{0, 0, 0};
    (s == 0 ? unit.x : s == 1 ? unit.y : unit.z) = 1;
    const Vec3 column = normalized(unit + c.lean);
    g.direction[s] = column.x, g.direction[3 + s] = column.y, g.direction[6 + s] = column.z;
    g.origin = g.origin - (column - unit) * (0.5 * g.spacing[s] * (g.dims[s] - 1));  // still around the phantom
    const std::vector<float> hu = phantom::sample(g, [&](const Vec3& p) { return shape.inside(p); });
    const std::string file = (cttest::scratch("slanted") / c.file).string();
    c.write(file, g, hu);
    const ct::CtVolume v = ct::readVolume(file);
    const double degrees = std::atan(norm(c.lean)) * 180 / M_PI;
    char slant[32];
    std::snprintf(slant, sizeof slant, "slanted by %.1f°", degrees);
    bool noted = false;
    for (const std::string& n : v.notes) noted = noted || n.find(slant) != std::string::npos;
    EXPECT_TRUE(noted) << slant << " in " << (v.notes.empty() ? "" : v.notes.back());
    // A voxel keeps its volume (which axis is taken as the slanted one may differ: a shear within the plane of
    // two axes slants either against the other).
    EXPECT_NEAR(v.spacing[0] * v.spacing[1] * v.spacing[2],
                g.spacing[0] * g.spacing[1] * g.spacing[2] * dot(column, unit), 1e-6);  // NIfTI: float32
    if (c.onlyReading) EXPECT_NEAR(v.spacing[s], g.spacing[s] * dot(column, unit), 1e-9);
    expectRectifiedPhantomInPlace(v, shape);
  }
}

}  // namespace
